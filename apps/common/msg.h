/* msg.h - messages and built paths as long as they need to be: a message that names a file is
 * never cut, however deep the file lies. Formatting measures first and allocates the exact size.
 */
#ifndef SC_MSG_H
#define SC_MSG_H

#include <stdarg.h>
#include <stdbool.h>

/* Lets the compiler check the format arguments of printf-like helpers. */
#if defined(__GNUC__)
#define SC_PRINTF_LIKE(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define SC_PRINTF_LIKE(fmt, args)
#endif

/* A message: text is NULL until one is set, then a heap string of exactly its length, or, when
 * that allocation failed, a fixed text saying so (never NULL once set). Zero-initialise it; free it
 * with sc_msg_free. */
typedef struct sc_msg {
    char *text;
} sc_msg;

/* The text a message holds when formatting it ran out of memory. */
#define SC_MSG_OUT_OF_MEMORY "out of memory while formatting a message"

/** Sets the message to printf-formatted text; the arguments may point into the message's own
 *  text ("%s: %s", path, msg->text puts a prefix before it). msg may be NULL: nothing happens. */
void sc_msg_set(sc_msg *msg, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);
/** sc_msg_set with a va_list. */
void sc_msg_vset(sc_msg *msg, const char *fmt, va_list ap) SC_PRINTF_LIKE(2, 0);
/** Appends printf-formatted text to the message (to "" when none is set); msg may be NULL. */
void sc_msg_append(sc_msg *msg, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);
/** sc_msg_append with a va_list. */
void sc_msg_vappend(sc_msg *msg, const char *fmt, va_list ap) SC_PRINTF_LIKE(2, 0);
/** The message's text: "" when none is set or msg is NULL. */
const char *sc_msg_text(const sc_msg *msg);
/** Frees the text and zeroes the message; a zeroed message is fine. */
void sc_msg_free(sc_msg *msg);

/** printf-formatted text as a new heap string of exactly its length (a joined path, say); NULL
 *  when out of memory. */
char *sc_format(const char *fmt, ...) SC_PRINTF_LIKE(1, 2);
/** sc_format with a va_list. */
char *sc_vformat(const char *fmt, va_list ap) SC_PRINTF_LIKE(1, 0);

#endif
