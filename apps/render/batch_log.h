/* batch_log.h - what a batch scheduler and its job monitors read of a run: one line per finished
 * item on stdout ("frame scene/0007.png 12.3 ms"; a still image's line is the caller's), a summary
 * line last, and with --progress-file the same events as JSON lines, flushed one by one. Used by
 * the rendering thread only. */
#ifndef BL_BATCH_LOG_H
#define BL_BATCH_LOG_H

#include <stdbool.h>
#include <stdio.h>

typedef struct batch_log {
    FILE *progress;   /* --progress-file, or NULL */
    const char *unit; /* "frames" or "images" */
    bool summary;     /* print the summary line at the end */
    long long items;  /* this run's (this shard's) */
    long long rendered, skipped;
    double start_ms;
} batch_log;

/** Opens progress_path to append to (a requeued task adds to its earlier lines); NULL: no file.
 *  False, with a message, when it cannot. Nothing is written yet. */
bool bl_open(batch_log *l, const char *progress_path);
/** Starts the run of `items` items (its shard I/N): the clock, and the progress file's first
 *  line. */
void bl_start(batch_log *l, bool frames, bool summary, long long items, int shard_index,
              int shard_count, bool resume);
/** An item written to disk in `ms` of rendering (< 0: not told): path is relative to the output
 *  folder. Frames
 *  get their stdout line here; with print false only the progress file hears of it. */
void bl_done(batch_log *l, const char *path, double ms, bool print);
/** An item already whole on disk (--resume): not rendered, no stdout line. */
void bl_skipped(batch_log *l, const char *path);
/** An item on disk that is not whole (--resume): said on stderr, rendered again. */
void bl_redo(batch_log *l, const char *prog, const char *out_dir, const char *path,
             const char *why);
/** The summary line (when asked for) and the progress file's last line; closes the file. status:
 *  the run's exit status. */
void bl_close(batch_log *l, int status);

#endif
