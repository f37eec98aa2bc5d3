/* frame_writer.c - a bounded queue of frames and the threads that write them (frame_writer.h). */
#define _GNU_SOURCE /* syscall */
#include "frame_writer.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "image_io.h"

/* One frame buffer, free or holding a frame to write. */
typedef struct slot {
    unsigned char *pixels;
    size_t cap;
    int width, height;
    char *path;
    double tag;
} slot;

struct frame_writer {
    pthread_mutex_t lock;
    pthread_cond_t changed; /* a frame was queued, written, or the writer is stopping */
    pthread_t *threads;
    int thread_count, level;
    slot *slots;
    int slot_count;
    /* Slot indices: free ones (a stack) and queued ones (a ring, oldest first). */
    int *free_list, free_count;
    int *queue, queue_head, queue_count;
    int busy; /* frames being written right now */
    /* Frames written and not yet collected: their paths (owned) and tags. */
    char **done_paths;
    double *done_tags;
    size_t done_count, done_cap;
    bool stopping, failed;
    sc_msg error; /* the first failure */
};

/* Appends a written frame to the done list (under the lock); false when out of memory. */
static bool record_done(frame_writer *w, char *path, double tag) {
    if (w->done_count == w->done_cap) {
        size_t cap = w->done_cap ? w->done_cap * 2 : 16;
        char **paths = realloc(w->done_paths, cap * sizeof *paths);
        if (paths) w->done_paths = paths;
        double *tags = paths ? realloc(w->done_tags, cap * sizeof *tags) : NULL;
        if (tags) w->done_tags = tags;
        if (!paths || !tags) return false;
        w->done_cap = cap;
    }
    w->done_paths[w->done_count] = path;
    w->done_tags[w->done_count++] = tag;
    return true;
}

static void *writer_main(void *arg) {
    frame_writer *w = arg;
    sc_msg err = {0};
    /* The renderer first: writing takes the cores it leaves idle (between frames, and while it
     * waits for a free slot) instead of taking turns with its workers, which would hold up
     * every frame's last bins. The lowest priority that still runs the thread; per thread on
     * Linux (elsewhere this is the process's, and left alone). */
#if defined(__linux__)
    (void)setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), 19);
#endif
    sc_png_writer *png = sc_png_writer_create(w->level);
    pthread_mutex_lock(&w->lock);
    if (!png && !w->failed) {
        w->failed = true;
        sc_msg_set(&w->error, "out of memory for a PNG writer");
    }
    for (;;) {
        while (w->queue_count == 0 && !w->stopping) pthread_cond_wait(&w->changed, &w->lock);
        if (w->queue_count == 0) break; /* stopping, and nothing left */
        int i = w->queue[w->queue_head];
        w->queue_head = (w->queue_head + 1) % w->slot_count;
        w->queue_count--;
        w->busy++;
        slot *s = &w->slots[i];
        /* After a failure the rest are dropped: the run ends with an error anyway. */
        bool skip = w->failed || !png;
        pthread_mutex_unlock(&w->lock);
        bool ok = skip || sc_png_writer_write(png, s->path, s->width, s->height, s->pixels, &err);
        pthread_mutex_lock(&w->lock);
        if (!ok && !w->failed) {
            w->failed = true;
            w->error = err; /* handed over whole */
            err = (sc_msg){0};
        }
        if (ok && !skip && !record_done(w, s->path, s->tag)) {
            if (!w->failed) {
                w->failed = true;
                sc_msg_set(&w->error, "out of memory");
            }
        } else if (ok && !skip) {
            s->path = NULL; /* the done list owns it now */
        }
        free(s->path);
        s->path = NULL;
        w->free_list[w->free_count++] = i;
        w->busy--;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    sc_msg_free(&err);
    sc_png_writer_destroy(png);
    return NULL;
}

static void free_writer(frame_writer *w) {
    for (int i = 0; i < w->slot_count; i++) {
        free(w->slots[i].pixels);
        free(w->slots[i].path);
    }
    for (size_t i = 0; i < w->done_count; i++) free(w->done_paths[i]);
    free(w->done_paths);
    free(w->done_tags);
    free(w->slots);
    free(w->free_list);
    free(w->queue);
    free(w->threads);
    sc_msg_free(&w->error);
    pthread_cond_destroy(&w->changed);
    pthread_mutex_destroy(&w->lock);
    free(w);
}

frame_writer *fw_start(const char *prog, int threads, int slots, int level) {
    frame_writer *w = calloc(1, sizeof *w);
    if (!w) {
        fprintf(stderr, "%s: out of memory\n", prog);
        return NULL;
    }
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->changed, NULL);
    w->level = level;
    w->slot_count = slots;
    w->slots = calloc((size_t)slots, sizeof *w->slots);
    w->free_list = calloc((size_t)slots, sizeof *w->free_list);
    w->queue = calloc((size_t)slots, sizeof *w->queue);
    w->threads = calloc((size_t)threads, sizeof *w->threads);
    if (!w->slots || !w->free_list || !w->queue || !w->threads) {
        fprintf(stderr, "%s: out of memory\n", prog);
        free_writer(w);
        return NULL;
    }
    for (int i = 0; i < slots; i++) w->free_list[w->free_count++] = i;
    for (; w->thread_count < threads; w->thread_count++) {
        if (pthread_create(&w->threads[w->thread_count], NULL, writer_main, w) != 0) {
            fprintf(stderr, "%s: cannot start a thread to write frames\n", prog);
            fw_stop(w);
            return NULL;
        }
    }
    return w;
}

unsigned char *fw_acquire(frame_writer *w, size_t bytes) {
    pthread_mutex_lock(&w->lock);
    while (w->free_count == 0 && !w->failed) pthread_cond_wait(&w->changed, &w->lock);
    unsigned char *out = NULL;
    if (!w->failed) {
        /* A free slot belongs to this thread alone until it is submitted. */
        slot *s = &w->slots[w->free_list[w->free_count - 1]];
        if (s->cap < bytes) {
            free(s->pixels);
            s->pixels = malloc(bytes);
            s->cap = s->pixels ? bytes : 0;
        }
        if (s->pixels) {
            w->free_count--;
            out = s->pixels;
        } else {
            w->failed = true;
            sc_msg_set(&w->error, "out of memory for a frame");
        }
    }
    pthread_mutex_unlock(&w->lock);
    return out;
}

bool fw_submit(frame_writer *w, unsigned char *pixels, int width, int height, const char *path,
               double tag) {
    pthread_mutex_lock(&w->lock);
    int i = 0;
    while (w->slots[i].pixels != pixels) i++;
    slot *s = &w->slots[i];
    s->width = width;
    s->height = height;
    s->tag = tag;
    s->path = strdup(path);
    if (!s->path && !w->failed) {
        w->failed = true;
        sc_msg_set(&w->error, "out of memory");
    }
    if (w->failed) {
        free(s->path);
        s->path = NULL;
        w->free_list[w->free_count++] = i;
    } else {
        w->queue[(w->queue_head + w->queue_count) % w->slot_count] = i;
        w->queue_count++;
        pthread_cond_broadcast(&w->changed);
    }
    bool ok = !w->failed;
    pthread_mutex_unlock(&w->lock);
    return ok;
}

bool fw_drain(frame_writer *w) {
    pthread_mutex_lock(&w->lock);
    while (w->queue_count > 0 || w->busy > 0) pthread_cond_wait(&w->changed, &w->lock);
    bool ok = !w->failed;
    pthread_mutex_unlock(&w->lock);
    return ok;
}

void fw_collect(frame_writer *w, void (*done)(void *ctx, const char *path, double tag), void *ctx) {
    /* The lists are taken whole, so the calls run without the lock (writers go on). */
    pthread_mutex_lock(&w->lock);
    char **paths = w->done_paths;
    double *tags = w->done_tags;
    size_t n = w->done_count;
    w->done_paths = NULL;
    w->done_tags = NULL;
    w->done_count = w->done_cap = 0;
    pthread_mutex_unlock(&w->lock);
    for (size_t i = 0; i < n; i++) {
        done(ctx, paths[i], tags[i]);
        free(paths[i]);
    }
    free(paths);
    free(tags);
}

const char *fw_error(const frame_writer *w) {
    return sc_msg_text(&w->error);
}

void fw_stop(frame_writer *w) {
    if (!w) return;
    pthread_mutex_lock(&w->lock);
    w->stopping = true;
    pthread_cond_broadcast(&w->changed);
    pthread_mutex_unlock(&w->lock);
    for (int i = 0; i < w->thread_count; i++) pthread_join(w->threads[i], NULL);
    free_writer(w);
}
