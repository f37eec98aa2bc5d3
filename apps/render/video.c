/* video.c - frames to GIF and MP4 through the ffmpeg program (video.h). */
#define _POSIX_C_SOURCE 200809L
#include "video.h"

#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "msg.h"

extern char **environ;

bool vd_parse_formats(const char *list, unsigned *formats, const char **bad, int *bad_len) {
    *formats = 0;
    const char *p = list;
    for (;;) {
        size_t n = strcspn(p, ",");
        if (n == 3 && !strncmp(p, "gif", 3)) {
            *formats |= VIDEO_GIF;
        } else if (n == 3 && !strncmp(p, "mp4", 3)) {
            *formats |= VIDEO_MP4;
        } else {
            *bad = p;
            *bad_len = (int)n;
            return false;
        }
        if (p[n] == '\0') return true;
        p += n + 1;
    }
}

const char *vd_extension(unsigned format) {
    return format == VIDEO_GIF ? "gif" : "mp4";
}

bool vd_have_ffmpeg(void) {
    const char *path = getenv("PATH");
    if (!path) return false;
    for (const char *p = path;;) {
        size_t n = strcspn(p, ":");
        /* An empty entry is the current folder, as the shell takes it. */
        char *file = sc_format("%.*s%sffmpeg", (int)n, n ? p : "", n ? "/" : "");
        bool found = file && access(file, X_OK) == 0;
        free(file);
        if (found) return true;
        if (p[n] == '\0') return false;
        p += n + 1;
    }
}

/* "file:" keeps a path that starts with '-' or holds a ':' a path to ffmpeg; an image sequence's
 * pattern needs its own '%' doubled. */
static char *ffmpeg_path(const char *path, bool pattern, const char *suffix) {
    size_t n = 5 + strlen(suffix) + 1;
    for (const char *c = path; *c; c++) n += (pattern && *c == '%') ? 2 : 1;
    char *out = malloc(n), *o = out;
    if (!out) return NULL;
    o += sprintf(o, "file:");
    for (const char *c = path; *c; c++) {
        *o++ = *c;
        if (pattern && *c == '%') *o++ = '%';
    }
    strcpy(o, suffix);
    return out;
}

bool vd_make(const char *prog, const char *dir, int digits, int frames, int fps, int width,
             unsigned format, const char *out_path) {
    char number[16], rate[16], count[16], name[16], filter[512];
    snprintf(name, sizeof name, "/%%0%dd.png", digits);
    snprintf(rate, sizeof rate, "%d", fps);
    snprintf(count, sizeof count, "%d", frames);
    snprintf(number, sizeof number, "%d", 0);
    char scale[96];
    if (format == VIDEO_GIF) {
        if (width > 0)
            snprintf(scale, sizeof scale, "scale=%d:-1:flags=lanczos,", width);
        else
            scale[0] = '\0';
        /* One palette for the whole animation from the pixels that change (stats_mode=diff), so
         * the moving subject gets the colours; an ordered dither does not crawl from frame to
         * frame as error diffusion does, and only the changed rectangle is re-encoded. */
        snprintf(filter, sizeof filter,
                 "%ssplit[a][b];[a]palettegen=stats_mode=diff[p];"
                 "[b][p]paletteuse=dither=bayer:bayer_scale=5:diff_mode=rectangle",
                 scale);
    } else if (width > 0) {
        snprintf(filter, sizeof filter, "scale=%d:-2:flags=lanczos", width - width % 2);
    } else {
        snprintf(filter, sizeof filter, "scale=trunc(iw/2)*2:trunc(ih/2)*2");
    }
    char *input = ffmpeg_path(dir, true, name), *output = ffmpeg_path(out_path, false, "");
    if (!input || !output) {
        fprintf(stderr, "%s: out of memory\n", prog);
        free(input);
        free(output);
        return false;
    }
    const char *gif[] = {"-loop", "0", NULL};
    /* H.264 in yuv420p (what browsers decode), near-transparent quality, the index at the front
     * so playback starts before the whole file has arrived. */
    const char *mp4[] = {"-c:v", "libx264",   "-pix_fmt",   "yuv420p", "-crf",
                         "18",   "-movflags", "+faststart", NULL};
    const char *argv[40];
    int n = 0;
    const char *head[] = {"ffmpeg",     "-nostdin", "-hide_banner",  "-loglevel", "error", "-y",
                          "-framerate", rate,       "-start_number", number,      "-i",    input,
                          "-frames:v",  count,      "-vf",           filter,      NULL};
    for (int i = 0; head[i]; i++) argv[n++] = head[i];
    for (const char **a = format == VIDEO_GIF ? gif : mp4; *a; a++) argv[n++] = *a;
    argv[n++] = output;
    argv[n] = NULL;
    pid_t pid;
    int rc = posix_spawnp(&pid, "ffmpeg", NULL, NULL, (char *const *)argv, environ);
    bool ok = false;
    if (rc != 0) {
        fprintf(stderr, "%s: cannot run ffmpeg: %s\n", prog, strerror(rc));
    } else {
        int status = 0;
        pid_t got;
        do got = waitpid(pid, &status, 0);
        while (got < 0 && errno == EINTR);
        ok = got == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        if (!ok) fprintf(stderr, "%s: ffmpeg failed to write %s\n", prog, out_path);
    }
    free(input);
    free(output);
    return ok;
}
