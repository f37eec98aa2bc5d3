/* progress.h - a one-line progress bar on stderr, redrawn in place: frames done of the total,
 * frames per second and the time left. Drawn only when stderr is a terminal, so logs stay clean. */
#ifndef PG_PROGRESS_H
#define PG_PROGRESS_H

#include <stdbool.h>

typedef struct progress {
    bool on;          /* drawing at all */
    bool shown;       /* a bar is on the screen now */
    long total, done; /* frames */
    double start_ms;  /* when the first frame started */
    double drawn_ms;  /* when the bar was last drawn */
    int drawn_len;    /* characters of the bar on the screen */
} progress;

/** A bar for `total` frames, starting now; off unless `wanted` and stderr is a terminal. */
void pg_init(progress *p, bool wanted, long total);
/** Counts `frames` more frames done; redraws the bar at most ten times a second, and at the end. */
void pg_step(progress *p, long frames);
/** Takes the bar off the screen (before printing a line of results); the next step redraws it. */
void pg_hide(progress *p);

#endif
