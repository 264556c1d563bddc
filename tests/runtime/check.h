/*
 * check.h - a tiny check macro for the runtime tests: failures are printed with file and
 * line, counting goes on; done() prints "N passed, M failed" and gives the exit status.
 */
#ifndef CHECK_H
#define CHECK_H

#include <stdio.h>

static unsigned long checks_passed, checks_failed;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (cond) {                                                                   \
            checks_passed++;                                                          \
        } else {                                                                      \
            checks_failed++;                                                          \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                    \
        }                                                                             \
    } while (0)

/* Equality of two integers, printing both on failure. */
#define CHECK_EQ(a, b)                                                                \
    do {                                                                              \
        unsigned long long a_ = (unsigned long long)(a), b_ = (unsigned long long)(b); \
        if (a_ == b_) {                                                               \
            checks_passed++;                                                          \
        } else {                                                                      \
            checks_failed++;                                                          \
            printf("FAIL %s:%d: %s == %s (0x%llX != 0x%llX)\n", __FILE__, __LINE__, #a, #b, \
                   a_, b_);                                                           \
        }                                                                             \
    } while (0)

/* Like CHECK_EQ with a label (an index, a loop counter) printed on failure. */
#define CHECK_EQ_AT(a, b, at)                                                         \
    do {                                                                              \
        unsigned long long a_ = (unsigned long long)(a), b_ = (unsigned long long)(b); \
        if (a_ == b_) {                                                               \
            checks_passed++;                                                          \
        } else {                                                                      \
            checks_failed++;                                                          \
            printf("FAIL %s:%d [%s=%ld]: %s == %s (0x%llX != 0x%llX)\n", __FILE__, __LINE__, \
                   #at, (long)(at), #a, #b, a_, b_);                                  \
        }                                                                             \
    } while (0)

static int done(void)
{
    printf("%lu passed, %lu failed\n", checks_passed, checks_failed);
    return checks_failed != 0;
}

#endif /* CHECK_H */
