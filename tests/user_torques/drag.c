/* Compiled user torques for the tests of gyrostat.CustomTorque (tests/user_torques/__init__.py):
 * int f(double t, const double *omega, const double *quaternion, double *moment, void *user_data). */
#include <math.h>
#include <stddef.h>

/* M = -c |omega| omega + (0, 0, a sin t), c = 0.05, a = 0.02 */
int quadratic_drag(double t, const double *w, const double *q, double *m, void *data) {
    (void)q, (void)data;
    const double norm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    m[0] = -0.05 * norm * w[0];
    m[1] = -0.05 * norm * w[1];
    m[2] = -0.05 * norm * w[2] + 0.02 * sin(t);
    return 0;
}

/* dM/domega = -c (|omega| I + omega omega^T / |omega|), row-major */
int quadratic_drag_jacobian(double t, const double *w, const double *q, double *d, void *data) {
    (void)t, (void)q, (void)data;
    const double norm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) d[3 * i + j] = -0.05 * ((i == j ? norm : 0.0) + w[i] * w[j] / norm);
    return 0;
}

/* M = -c omega, c = *(double *)data */
int linear_drag(double t, const double *w, const double *q, double *m, void *data) {
    (void)t, (void)q;
    const double c = *(const double *)data;
    for (int i = 0; i < 3; ++i) m[i] = -c * w[i];
    return 0;
}

/* fails (returns 3) after t = 1 */
int failing(double t, const double *w, const double *q, double *m, void *data) {
    (void)w, (void)q, (void)data;
    m[0] = m[1] = m[2] = 0.0;
    return t > 1.0 ? 3 : 0;
}
