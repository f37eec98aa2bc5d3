/* batch_log.c - item lines, the summary and the progress file (batch_log.h). */
#define _POSIX_C_SOURCE 200809L
#include "batch_log.h"

#include <errno.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* s as a JSON string, quotes included. */
static void put_json_string(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* Ends a progress line: flushed at once, so a monitor (or a task killed next) sees it. */
static void end_line(FILE *f) {
    fputs("}\n", f);
    fflush(f);
}

bool bl_open(batch_log *l, const char *progress_path) {
    memset(l, 0, sizeof *l);
    if (!progress_path) return true;
    l->progress = fopen(progress_path, "a");
    if (!l->progress) {
        fprintf(stderr, "sgapi-render: --progress-file: cannot open '%s': %s\n", progress_path,
                strerror(errno));
        return false;
    }
    return true;
}

void bl_start(batch_log *l, bool frames, bool summary, long long items, int shard_index,
              int shard_count, bool resume) {
    l->unit = frames ? "frames" : "images";
    l->summary = summary;
    l->items = items;
    l->start_ms = now_ms();
    if (!l->progress) return;
    fprintf(l->progress,
            "{\"event\": \"start\", \"unit\": \"%s\", \"items\": %lld, \"shard\": [%d, %d], "
            "\"resume\": %s, \"pid\": %ld",
            l->unit, items, shard_index, shard_count, resume ? "true" : "false", (long)getpid());
    end_line(l->progress);
}

static void progress_item(batch_log *l, const char *event, const char *path) {
    fprintf(l->progress, "{\"event\": \"%s\", \"path\": ", event);
    put_json_string(l->progress, path);
}

void bl_done(batch_log *l, const char *path, double ms, bool print) {
    l->rendered++;
    if (print) {
        printf("frame %s %.2f ms\n", path, ms);
        fflush(stdout);
    }
    if (!l->progress) return;
    progress_item(l, "done", path);
    if (ms >= 0) fprintf(l->progress, ", \"ms\": %.3f", ms);
    fprintf(l->progress, ", \"finished\": %lld, \"items\": %lld", l->rendered + l->skipped,
            l->items);
    end_line(l->progress);
}

void bl_skipped(batch_log *l, const char *path) {
    l->skipped++;
    if (!l->progress) return;
    progress_item(l, "skipped", path);
    fprintf(l->progress, ", \"finished\": %lld, \"items\": %lld", l->rendered + l->skipped,
            l->items);
    end_line(l->progress);
}

void bl_redo(batch_log *l, const char *prog, const char *out_dir, const char *path,
             const char *why) {
    fprintf(stderr, "%s: --resume: %s/%s %s: rendering it again\n", prog, out_dir, path, why);
    if (!l->progress) return;
    progress_item(l, "redo", path);
    fputs(", \"reason\": ", l->progress);
    put_json_string(l->progress, why);
    end_line(l->progress);
}

void bl_close(batch_log *l, int status) {
    if (!l->unit) { /* opened, never started: the run stopped before it began */
        if (l->progress) fclose(l->progress);
        l->progress = NULL;
        return;
    }
    double seconds = (now_ms() - l->start_ms) / 1e3;
    long long finished = l->rendered + l->skipped, missing = l->items - finished;
    if (l->summary) {
        printf("%s: %lld of %lld %s on disk (%lld rendered, %lld already there)",
               status == 0 ? "done" : "failed", finished, l->items, l->unit, l->rendered,
               l->skipped);
        if (status != 0) printf(", %lld not done", missing);
        printf(" in %.3f s\n", seconds);
        fflush(stdout);
    }
    if (l->progress) {
        fprintf(l->progress,
                "{\"event\": \"end\", \"status\": %d, \"items\": %lld, \"rendered\": %lld, "
                "\"skipped\": %lld, \"not_done\": %lld, \"seconds\": %.3f",
                status, l->items, l->rendered, l->skipped, missing, seconds);
        end_line(l->progress);
        fclose(l->progress);
        l->progress = NULL;
    }
}
