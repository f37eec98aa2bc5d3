/* progress.c - the progress bar of sgapi-render (progress.h). */
#define _POSIX_C_SOURCE 200809L
#include "progress.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

void pg_init(progress *p, bool wanted, long total) {
    memset(p, 0, sizeof *p);
    p->on = wanted && total > 0 && isatty(STDERR_FILENO);
    p->total = total;
    p->start_ms = now_ms();
}

/* "1:05" or "1:02:05". */
static void format_time(double seconds, char *out, size_t len) {
    long s = seconds < 0 ? 0 : (long)(seconds + 0.5);
    if (s >= 3600)
        snprintf(out, len, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else
        snprintf(out, len, "%ld:%02ld", s / 60, s % 60);
}

static void draw(progress *p, double now) {
    enum { BAR = 30 };
    char bar[BAR + 1], left[32], line[160];
    long filled = p->total ? p->done * BAR / p->total : BAR;
    for (int i = 0; i < BAR; i++) bar[i] = i < filled ? '#' : '.';
    bar[BAR] = '\0';
    double seconds = (now - p->start_ms) / 1e3;
    double fps = seconds > 0 ? (double)p->done / seconds : 0.0;
    if (fps > 0)
        format_time((double)(p->total - p->done) / fps, left, sizeof left);
    else
        snprintf(left, sizeof left, "-:--");
    int n = snprintf(line, sizeof line, "[%s] %ld/%ld frames  %.1f fps  %s left", bar, p->done,
                     p->total, fps, left);
    if (n < 0) return;
    if (n >= (int)sizeof line) n = (int)sizeof line - 1;
    /* Spaces, not an escape sequence, clear what a longer bar left: any terminal does that. */
    fprintf(stderr, "\r%s%*s", line, p->drawn_len > n ? p->drawn_len - n : 0, "");
    fflush(stderr);
    p->drawn_len = n;
    p->drawn_ms = now;
    p->shown = true;
}

void pg_step(progress *p, long frames) {
    p->done += frames;
    if (!p->on) return;
    double now = now_ms();
    if (!p->shown || now - p->drawn_ms >= 100.0 || p->done >= p->total) draw(p, now);
}

void pg_hide(progress *p) {
    if (!p->on || !p->shown) return;
    fprintf(stderr, "\r%*s\r", p->drawn_len, "");
    fflush(stderr);
    p->shown = false;
    p->drawn_len = 0;
}
