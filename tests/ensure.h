/* ensure.h - what the test programs share: ENSURE(c) and ENSURE_NEAR(a, b, tol), which print the
   failing line and return 1 from the test function, and a monotonic wall clock. Include after
   <stdio.h>, <math.h> and <time.h> (with _POSIX_C_SOURCE >= 199309L for clock_gettime). */
#ifndef SPS_TESTS_ENSURE_H
#define SPS_TESTS_ENSURE_H

#define ENSURE(c)                                                                   \
    do {                                                                            \
        if (!(c)) {                                                                 \
            printf("    %s:%d: ENSURE(%s) failed\n", __FILE__, __LINE__, #c);       \
            return 1;                                                               \
        }                                                                           \
    } while (0)

/* Fails on NaN too: !(|a - b| <= tol). */
#define ENSURE_NEAR(a, b, tol)                                                                      \
    do {                                                                                            \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                              \
        if (!(fabs(a_ - b_) <= t_)) {                                                               \
            printf("    %s:%d: ENSURE_NEAR(%s, %s, %s) failed: %.17g vs %.17g, |diff| %.3g > %.3g\n", \
                   __FILE__, __LINE__, #a, #b, #tol, a_, b_, fabs(a_ - b_), t_);                     \
            return 1;                                                                               \
        }                                                                                           \
    } while (0)

static double wall_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
#endif
