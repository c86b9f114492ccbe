/* sin, cos and sincos with the same bits on every machine (detmath.h).
 *
 *   fb_sin,    x = k pi/2 + r: Cody & Waite reduction with pi/2 in four parts (33+33+33+53 bits, exact products
 *   fb_cos,    for |k| < 2^20) for |x| < 1.6e6, Payne & Hanek's reduction (SIGNUM Newsletter 18(1), 1983) with
 *   fb_sincos  1280 bits of 2/pi in integer arithmetic beyond: r as a double-double, absolute error < 2^-127
 *              (|r| >= 2^-61.5 for every double, 2^-60.5 below 1.6e6: relative error < 2^-65).  Then
 *              a table of sin and cos at a = i/64 in double-double (Gal & Bachelis, ACM TOMS 17(1), 1991, use
 *              the same addition formulas): sin(a + d), cos(a + d) with |d| <= 1/128 from Taylor polynomials,
 *              the leading products exact.  Error < 0.502 ulp for every finite x (no range limit); sin and cos
 *              of fb_sincos are the bits of fb_sin and fb_cos (the same code).
 *
 * The reductions, the kernel and their tables (detmath_tab_trig.h) are static in this one file, inlined into
 * the three functions: fb_sincos is on the hot path of the kernels.
 */
#include "detmath.h"
#include "detmath_dd.h"
#include "detmath_tab_trig.h"
#include "detmath_tables.h"

/* the bits of 2/pi from offset o (0 = the first bit after the binary point), 64 of them */
static inline uint64_t two_over_pi_bits(int o) {
    int w = o >> 6, b = o & 63;
    uint64_t v = TWO_OVER_PI[w] << b;
    if (b) v |= TWO_OVER_PI[w + 1] >> (64 - b);
    return v;
}

/* the 128-bit product a b = hi 2^64 + lo (32-bit limbs: portable C99) */
static inline void mul64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo) {
    uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
    *lo = (mid << 32) | (p00 & 0xffffffffu);
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

/* bits pos .. pos+63 of the 320-bit integer p[0] + p[1] 2^64 + ... */
static inline uint64_t bits_at(const uint64_t p[5], int pos) {
    int w = pos >> 6, b = pos & 63;
    uint64_t v = p[w] >> b;
    if (b) v |= p[w + 1] << (64 - b);
    return v;
}

/* Payne & Hanek: x = M 2^e (M a 53-bit integer, x >= 2^20) times 2/pi modulo 4, in integer arithmetic.  The
 * bits b_i 2^-i of 2/pi with i <= e - 2 give multiples of 4 and are skipped; 192 bits from i0 = max(1, e - 1)
 * give the product P = M W with s = i0 + 191 - e >= 190 fraction bits, truncation error < 2^(53 - s).  The
 * fraction f in [-1/2, 1/2) (128 bits) times pi/2 is r; the quadrant is the integer part mod 4. */
static int reduce_large(double ax, double *rh, double *rl) {
    uint64_t ix = bits_of(ax);
    int e = (int)(ix >> 52) - 1075;
    uint64_t M = (ix & 0x000fffffffffffffULL) | (1ULL << 52);
    int i0 = e - 1 > 1 ? e - 1 : 1;
    int s = i0 + 191 - e, o = i0 - 1;
    uint64_t w2 = two_over_pi_bits(o), w1 = two_over_pi_bits(o + 64), w0 = two_over_pi_bits(o + 128);
    uint64_t h0, l0, h1, l1, h2, l2, p[5];
    mul64(M, w0, &h0, &l0);
    mul64(M, w1, &h1, &l1);
    mul64(M, w2, &h2, &l2);
    p[0] = l0;
    p[1] = h0 + l1;
    uint64_t c1 = p[1] < l1;
    p[2] = h1 + l2;
    uint64_t c2 = p[2] < l2;
    p[2] += c1;
    c2 += p[2] < c1;
    p[3] = h2 + c2;
    p[4] = 0;
    uint64_t fh = bits_at(p, s - 64), fl = bits_at(p, s - 128);
    int q = (int)(bits_at(p, s) & 3);
    double sg = 1.0;
    if (fh >> 63) { /* f >= 1/2: the next quadrant, f - 1 = -(2^128 - F) 2^-128 */
        q = (q + 1) & 3;
        sg = -1.0;
        fl = ~fl + 1;
        fh = ~fh + (fl == 0);
    }
    int sh = 0; /* normalize F (|f| >= 2^-62 for every double x, so fh != 0 in practice) */
    if (fh == 0) {
        fh = fl;
        fl = 0;
        sh = 64;
        if (fh == 0) {
            *rh = *rl = 0.0;
            return q;
        }
    }
    while (!(fh >> 63)) {
        fh = (fh << 1) | (fl >> 63);
        fl <<= 1;
        sh++;
    }
    /* f = fh 2^(-64-sh) + fl 2^(-128-sh): the top 53 bits and the next 53 as an exact double-double */
    double f1 = (double)(fh >> 11) * pow2i(-53 - sh);
    double f2 = (double)(((fh & 0x7ffu) << 42) | (fl >> 22)) * pow2i(-106 - sh);
    dd r = two_prod(f1, PIO2_HI);
    r = fast_two_sum(r.hi, r.lo + (f1 * PIO2_LO + f2 * PIO2_HI));
    *rh = sg * r.hi;
    *rl = sg * r.lo;
    return q;
}

/* ax = |x| finite: the quadrant q (k mod 4) and r = ax - k pi/2 = rh + rl, |r| <= pi/4 + 2^-30, absolute error
 * < 2^-134 (k P4's rounding; |r| >= 2^-60.5 for every double below 1.6e6: the doubles nearest to k pi/2, all
 * k < 2^20, were checked); k = 0 gives r = ax */
static inline int reduce_pio2(double ax, double *rh, double *rl) {
    if (ax < 1.6e6) { /* |k| < 2^20: Cody & Waite, k P1, k P2, k P3 exact */
        double kd = round_int(ax * INV_PIO2);
        double a = ax - kd * PIO2_1; /* exact: kd P1 is within a factor 2 of ax, or kd = 0 */
        double b = kd * PIO2_2, c = kd * PIO2_3, d = kd * PIO2_4;
        double h = a - b;
        if (fabs(h) >= 0x1p-13) { /* |a| >= |b| (< 2^-14) and |h| >= |c| (< 2^-49): fast_two_sum for both */
            double e1 = (a - h) - b;
            double g = h - c;
            double e2 = (h - g) - c;
            *rh = g;
            *rl = (e1 + e2) - d;
        } else { /* r near 0 (rare): the exact sums of two_sum */
            dd hh = two_sum(a, -b);
            dd gg = two_sum(hh.hi, -c);
            dd r = fast_two_sum(gg.hi, (hh.lo + gg.lo) - d); /* |r| >= 2^-61 >> the tail */
            *rh = r.hi;
            *rl = r.lo;
        }
        return (int)kd & 3;
    }
    return reduce_large(ax, rh, rl);
}

/* sin and cos of r = rh + rl, |r| <= pi/4 + 2^-30, |rl| <= 2 ulp(rh): r = a + d with a = i/64, |d| <= 1/128,
 * sin(a + d) = sin a + cos a d + [cos a (sin d - d) + sin a (cos d - 1)],
 * cos(a + d) = cos a - sin a d + [cos a (cos d - 1) - sin a (sin d - d)],
 * sin a d and cos a d exact (Dekker's product with the table's split of sin a, cos a).  Computed for |r|, the
 * sign of sin r returned in *neg (a sign bit); no branch (the signs of r are random in a simulation), the
 * sums ordered as shallow trees (the kernel is latency-bound). */
static inline void sincos_kernel(double rh, double rl, double *sr, double *cr, uint64_t *neg) {
    uint64_t sgn = bits_of(rh) & 0x8000000000000000ULL;
    rh = double_of(bits_of(rh) ^ sgn);
    rl = double_of(bits_of(rl) ^ sgn);
    double ta = rh + 0x1.8p46; /* rh rounded to a multiple of 2^-6 (ulp of 1.5 2^46), exactly */
    double a = ta - 0x1.8p46;
    int i = (int)(bits_of(ta) & 0xff);
    const double *t = SINCOS_TAB + 8 * i;
    double d = rh - a; /* exact (Sterbenz for i >= 1) */
    double z = d * d, z2 = z * z;
    /* sin d - d to d^7 and cos d - 1 to d^8 (the next terms are < 2^-81 |d| and < 2^-91) */
    double ps = (d * z) * (-0x1.5555555555555p-3 + z * 0x1.1111111111111p-7) + (d * z2) * (z * -0x1.a01a01a01a01ap-13);
    double pc = (z * (-0.5 + z * 0x1.5555555555555p-5) + (z * z2) * (-0x1.6c16c16c16c17p-10 + z * 0x1.a01a01a01a01ap-16)) -
                d * rl;
    double ds = rl + ps; /* sin(d + rl) = d + ds, cos(d + rl) = 1 + pc */
    double dh, dl;
    split(d, &dh, &dl);
    double S = t[0], Sh = t[1], St = t[2], Sl = t[3], C = t[4], Ch = t[5], Ct = t[6], Cl = t[7];
    double pC = C * d, eC = ((Ch * dh - pC) + Ch * dl + Ct * dh) + Ct * dl; /* C d = pC + eC */
    double pS = S * d, eS = ((Sh * dh - pS) + Sh * dl + St * dh) + St * dl; /* S d = pS + eS */
    dd s = fast_two_sum(S, pC); /* |S| >= sin(1/64) > |pC| or S = 0 */
    dd c = fast_two_sum(C, -pS);
    *sr = s.hi + ((s.lo + eC) + ((C * ds + S * pc) + (Sl + Cl * d)));
    *cr = c.hi + ((c.lo - eS) + ((C * pc - S * ds) + (Cl - Sl * d)));
    *neg = sgn;
}

/* sin x and cos x: x = k pi/2 + r, q = k mod 4; sin x = (sin r, cos r, -sin r, -cos r)[q] and
 * cos x = (cos r, -sin r, -cos r, sin r)[q], selected and signed with bit masks (no branch on q) */
static inline void sincos_core(double x, double *s, double *c) {
    double ax = fabs(x);
    if (!(ax < INFINITY)) { /* +-inf, NaN */
        *s = *c = x - x;
        return;
    }
    double rh, rl, sr, cr;
    uint64_t neg;
    int q = reduce_pio2(ax, &rh, &rl);
    sincos_kernel(rh, rl, &sr, &cr, &neg);
    uint64_t us = bits_of(sr) ^ neg, uc = bits_of(cr); /* sin r, cos r with their signs */
    uint64_t swap = -(uint64_t)(q & 1);
    uint64_t vs = (us & ~swap) | (uc & swap), vc = (uc & ~swap) | (us & swap);
    uint64_t ns = (uint64_t)((q >> 1) & 1) << 63, nc = (uint64_t)(((q + 1) >> 1) & 1) << 63;
    *s = double_of(vs ^ ns ^ (bits_of(x) & 0x8000000000000000ULL));
    *c = double_of(vc ^ nc);
}

double fb_sin(double x) {
    double s, c;
    sincos_core(x, &s, &c);
    return s;
}

double fb_cos(double x) {
    double s, c;
    sincos_core(x, &s, &c);
    return c;
}

void fb_sincos(double x, double *s, double *c) { sincos_core(x, s, c); }
