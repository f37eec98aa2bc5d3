/* msg.c - messages and paths of exactly their length (see msg.h). */
#include "msg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Returned instead of a message that could not be allocated; never freed, never written. */
static const char out_of_memory[] = SC_MSG_OUT_OF_MEMORY;

char *sc_vformat(const char *fmt, va_list ap) {
    va_list measure;
    va_copy(measure, ap);
    int n = vsnprintf(NULL, 0, fmt, measure);
    va_end(measure);
    if (n < 0) return NULL;
    char *s = malloc((size_t)n + 1);
    if (s) vsnprintf(s, (size_t)n + 1, fmt, ap);
    return s;
}

char *sc_format(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    char *s = sc_vformat(fmt, ap);
    va_end(ap);
    return s;
}

/* Replaces the text by `text` (NULL: out of memory), freeing the old one after: the new text may
 * have been made from it. */
static void replace(sc_msg *msg, char *text) {
    char *old = msg->text;
    msg->text = text ? text : (char *)out_of_memory;
    if (old != out_of_memory) free(old);
}

void sc_msg_vset(sc_msg *msg, const char *fmt, va_list ap) {
    if (msg) replace(msg, sc_vformat(fmt, ap));
}

void sc_msg_set(sc_msg *msg, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vset(msg, fmt, ap);
    va_end(ap);
}

void sc_msg_vappend(sc_msg *msg, const char *fmt, va_list ap) {
    if (!msg || msg->text == out_of_memory) return;
    char *tail = sc_vformat(fmt, ap);
    if (!tail) {
        replace(msg, NULL);
        return;
    }
    replace(msg, msg->text ? sc_format("%s%s", msg->text, tail) : tail);
    if (msg->text != tail) free(tail);
}

void sc_msg_append(sc_msg *msg, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vappend(msg, fmt, ap);
    va_end(ap);
}

const char *sc_msg_text(const sc_msg *msg) {
    return msg && msg->text ? msg->text : "";
}

void sc_msg_free(sc_msg *msg) {
    if (!msg) return;
    replace(msg, NULL);
    msg->text = NULL;
}
