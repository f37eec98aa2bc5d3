/* frame_writer.h - PNG frames encoded and written on threads of their own while the next frames
 * render, through a bounded queue: at most `slots` frames are held at once, so memory stays
 * bounded however long the animation. */
#ifndef FW_FRAME_WRITER_H
#define FW_FRAME_WRITER_H

#include <stdbool.h>
#include <stddef.h>

typedef struct frame_writer frame_writer;

/** Starts `threads` writer threads (>= 1) with `slots` frame buffers (>= threads + 1) and PNG
 *  compression level `level`; NULL (with a message) on failure. */
frame_writer *fw_start(const char *prog, int threads, int slots, int level);
/** A buffer of at least `bytes` for the next frame's pixels: waits while every buffer is queued.
 *  NULL when out of memory or a write has failed (fw_error says why). */
unsigned char *fw_acquire(frame_writer *w, size_t bytes);
/** Queues the acquired buffer to be written as an RGBA8 PNG at `path` (copied); `tag` comes back
 *  with the path from fw_collect once the file is written. False when a write has failed; the
 *  buffer goes back to the writer either way. */
bool fw_submit(frame_writer *w, unsigned char *pixels, int width, int height, const char *path,
               double tag);
/** Calls done(ctx, path, tag) for every frame written since the last call, in the order they were
 *  written, on the calling thread (so the caller's output needs no lock). */
void fw_collect(frame_writer *w, void (*done)(void *ctx, const char *path, double tag), void *ctx);
/** Waits until every queued frame is written; false when any write failed. */
bool fw_drain(frame_writer *w);
/** The first write error ("" if none). */
const char *fw_error(const frame_writer *w);
/** Writes what is queued, stops the threads and frees everything; NULL is fine. */
void fw_stop(frame_writer *w);

#endif
