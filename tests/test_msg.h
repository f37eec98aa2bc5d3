/* test_msg.h - the loaders' messages (sc_msg) in tests: one freed when it goes out of scope, and
 * its text ("" when none is set). */
#ifndef TEST_MSG_H
#define TEST_MSG_H

#include "msg.h"

/* Declares an empty message `name`, freed at the end of its scope (GCC and clang). */
#define TEST_MSG(name) sc_msg name __attribute__((cleanup(sc_msg_free))) = {0}
/* The text of a message declared with TEST_MSG. */
#define MSG(name) sc_msg_text(&(name))

#endif
