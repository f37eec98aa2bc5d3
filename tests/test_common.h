/* test_common.h - includes every cmocka test needs, in the order cmocka requires. */
#ifndef SG_TEST_COMMON_H
#define SG_TEST_COMMON_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#endif
