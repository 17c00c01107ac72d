/* tests/check.h — a minimal test harness: CHECK* macros record failures and keep going;
 * CHECK_DONE() prints "N passed, M failed" and returns the exit status from main. */
#ifndef SSS_TEST_CHECK_H
#define SSS_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed_, check_failed_;

#define CHECK(cond) \
    do { \
        if (cond) check_passed_++; \
        else { check_failed_++; fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

#define CHECK_MSG(cond, ...) \
    do { \
        if (cond) check_passed_++; \
        else { check_failed_++; fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
               fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); } \
    } while (0)

/* |a - b| <= tol */
#define CHECK_NEAR(a, b, tol) \
    do { \
        double a_ = (a), b_ = (b), t_ = (tol); \
        if (fabs(a_ - b_) <= t_) check_passed_++; \
        else { check_failed_++; fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %.3g\n", \
                                        __FILE__, __LINE__, #a, a_, #b, b_, t_); } \
    } while (0)

/* |a - b| <= rel * |b| */
#define CHECK_REL(a, b, rel) \
    do { \
        double a_ = (a), b_ = (b), r_ = (rel); \
        if (fabs(a_ - b_) <= r_ * fabs(b_)) check_passed_++; \
        else { check_failed_++; fprintf(stderr, "%s:%d: CHECK_REL failed: %s = %.9g, %s = %.9g, rel %.3g (is %.3g)\n", \
                                        __FILE__, __LINE__, #a, a_, #b, b_, r_, fabs(a_ - b_) / fabs(b_)); } \
    } while (0)

#define CHECK_DONE() \
    (printf("%d passed, %d failed\n", check_passed_, check_failed_), check_failed_ ? 1 : 0)

#endif
