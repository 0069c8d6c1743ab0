/* Reference C loop of the tip model's recurrence (paper Eqs 2-10) with the Masing energies,
 * the same arithmetic as microslip.models.batch_kernels.tip_kernel (consistent Poisson update,
 * length update on, secant strain energy), for benchmarks/bench_batch.py.
 *
 * Usage: ref_tip CASES INCREMENTS MODE OUT.bin
 *   MODE "sequential": one case after another (the recurrence runs increment by increment,
 *                      so each step waits for the previous one: latency bound);
 *   MODE "interleaved": blocks of LANES cases advanced together, increment by increment
 *                      (independent cases fill the pipeline, the lane loop vectorises).
 * Cases: the Table 2 tip preset (L 50 mm, w 10 mm, t 25 mm, E 10000 MPa, nu 0.3, mu 0.8,
 * F_N 20000 N) at amplitudes evenly spaced from 100 N to 8000 N.
 * Prints the compute time in seconds; writes the loss factor of every case (float64).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define LANES 256
#define PI 3.14159265358979323846

static const double L0 = 50.0, W0 = 10.0, T0 = 25.0, E = 10000.0, NU = 0.3, MU = 0.8,
                    FN = 20000.0;

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Advance m cases (m <= LANES) through n increments; eta out. */
static void block(const double *restrict f0, int m, int n, double *restrict eta) {
    double d[LANES], ra[LANES], q[LANES];
    const double rfn = 1.0 / (MU * FN), cnu = NU / E, he = 0.5 / E;
    for (int k = 0; k < m; k++) {
        d[k] = 0.0;
        q[k] = 0.0;
        ra[k] = 1.0 / (W0 * T0);
    }
    double fr_prev = 0.0;
    for (int i = 1; i <= n; i++) {
        const double fr = (double)i / n;
        for (int k = 0; k < m; k++) {
            const double f = f0[k] * fr, fp = f0[k] * fr_prev;
            const double u = f * (L0 + d[k]) * rfn;
            const double g = 1.0 - cnu * (f - fp) * ra[k];
            const double ra_new = ra[k] / (g * g);
            const double dn = f * u * he * ra_new;
            q[k] += (fp + f) * (dn - d[k]);
            d[k] = dn;
            ra[k] = ra_new;
        }
        fr_prev = fr;
    }
    for (int k = 0; k < m; k++) {
        const double w = 4.0 * (q[k] - f0[k] * d[k]);
        eta[k] = w / (2.0 * PI * (0.5 * f0[k] * d[k]));
    }
}

/* One case, increment after increment: every step depends on the one before. */
static double one_case(double f0, int n) {
    double d = 0.0, q = 0.0, ra = 1.0 / (W0 * T0);
    const double rfn = 1.0 / (MU * FN), cnu = NU / E, he = 0.5 / E;
    double fr_prev = 0.0;
    for (int i = 1; i <= n; i++) {
        const double fr = (double)i / n;
        const double f = f0 * fr, fp = f0 * fr_prev;
        const double u = f * (L0 + d) * rfn;
        const double g = 1.0 - cnu * (f - fp) * ra;
        const double ra_new = ra / (g * g);
        const double dn = f * u * he * ra_new;
        q += (fp + f) * (dn - d);
        d = dn;
        ra = ra_new;
        fr_prev = fr;
    }
    const double w = 4.0 * (q - f0 * d);
    return w / (2.0 * PI * (0.5 * f0 * d));
}

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: %s CASES INCREMENTS sequential|interleaved OUT.bin\n", argv[0]);
        return 2;
    }
    const long cases = atol(argv[1]);
    const int n = atoi(argv[2]);
    const int interleaved = strcmp(argv[3], "interleaved") == 0;
    if (cases < 1 || n < 1 || (!interleaved && strcmp(argv[3], "sequential") != 0)) {
        fprintf(stderr, "bad arguments\n");
        return 2;
    }
    double *f0 = malloc(cases * sizeof(double)), *eta = malloc(cases * sizeof(double));
    if (!f0 || !eta) return 1;
    for (long j = 0; j < cases; j++)  /* numpy.linspace(100, 8000, cases) */
        f0[j] = cases > 1 ? 100.0 + j * ((8000.0 - 100.0) / (cases - 1)) : 100.0;
    if (cases > 1) f0[cases - 1] = 8000.0;
    const double t0 = now();
    if (interleaved) {
        for (long lo = 0; lo < cases; lo += LANES) {
            const int m = (int)(cases - lo < LANES ? cases - lo : LANES);
            block(f0 + lo, m, n, eta + lo);
        }
    } else {
        for (long j = 0; j < cases; j++) eta[j] = one_case(f0[j], n);
    }
    const double t1 = now();
    FILE *fh = fopen(argv[4], "wb");
    if (!fh || fwrite(eta, sizeof(double), cases, fh) != (size_t)cases) return 1;
    fclose(fh);
    printf("%.6f\n", t1 - t0);
    free(f0);
    free(eta);
    return 0;
}
