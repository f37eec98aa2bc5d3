/* video.h - a turntable's frames made into a GIF and an MP4 by the ffmpeg program. The ffmpeg
 * options live here alone: rendering and the final step of a sharded run (--assemble) both call
 * this. */
#ifndef VD_VIDEO_H
#define VD_VIDEO_H

#include <stdbool.h>

/* Formats, as bits of a set. */
enum { VIDEO_GIF = 1, VIDEO_MP4 = 2 };

/** Parses a comma-separated list of formats ("gif", "mp4", "gif,mp4") into a set; false (and
 *  the offending name as the bad_len bytes at *bad, inside list) for an unknown or empty name. */
bool vd_parse_formats(const char *list, unsigned *formats, const char **bad, int *bad_len);
/** Whether an executable ffmpeg is on PATH. */
bool vd_have_ffmpeg(void);
/** The file name extension of one format: "gif" or "mp4". */
const char *vd_extension(unsigned format);
/** Runs ffmpeg on the frames dir/0000.png .. (digits wide, from 0) to write one format at fps
 *  frames a second: a palette-optimised GIF, or H.264 in yuv420p with the index up front (plays in
 *  browsers). width > 0 scales the video to that width (keeping the aspect), else it keeps the
 *  frames' size (an MP4 one pixel less on an odd side: yuv420p halves both). False, with
 *  ffmpeg's messages on stderr, on failure. */
bool vd_make(const char *prog, const char *dir, int digits, int frames, int fps, int width,
             unsigned format, const char *out_path);

#endif
