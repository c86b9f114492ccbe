/* Internal to the detmath*.c files: the tables (defined in detmath_tab_*.c; sin and cos have theirs in
 * detmath_tab_trig.h) and the constants of the elementary functions.
 *
 * The tables were generated with mpmath at 400 bits (each table file holds its recipe).  A double-double
 * entry is (nearest double to v, nearest double to v - hi).
 *
 * EXP2_TAB[2j], [2j+1]: 2^(j/64), j = 0..63 (detmath_tab_exp2.c).
 * LOG_INVC[i]: c_i, 1/(centre of mantissa interval i) rounded to 12 significant bits (1 for i = 0 and 255);
 *   interval i is [1 + i/256, 1 + (i+1)/256), halved for i >= 106.  LOG_LOGC[2i], [2i+1]: -log(c_i)
 *   (detmath_tab_log.c).
 * ATAN_TAB[2i], [2i+1]: atan(i/64), i = 0..64 (detmath_tab_atan.c).
 *
 * Recipe of the constants (Python, mpmath at 400 bits, round_bits as in detmath_tab_log.c): EXP_L1 =
 * round_bits(ln2/64, 36), LN2_HI = round_bits(ln2, 42), PIO2_1..3 = 33-bit roundings of pi/2 minus the
 * previous parts, the others the nearest doubles (a _LO part: the nearest double to the value minus its _HI
 * part); the polynomial coefficients in the functions are the nearest doubles to 1/n!, 1/n and
 * B_2k / (2k (2k-1)).
 */
#ifndef FLEXBEAM_DETMATH_TABLES_H
#define FLEXBEAM_DETMATH_TABLES_H

#include <stdint.h>

/* ------------------------------------------------------------------------------------------------------ tables */
/* hidden: not exported from the extension, and read directly (pc-relative) rather than through the GOT, as the
 * static tables of one file were */
#if defined(__GNUC__)
#define FB_DETMATH_HIDDEN __attribute__((visibility("hidden")))
#else
#define FB_DETMATH_HIDDEN
#endif

extern FB_DETMATH_HIDDEN const double EXP2_TAB[128];
extern FB_DETMATH_HIDDEN const double LOG_INVC[256];
extern FB_DETMATH_HIDDEN const double LOG_LOGC[512];
extern FB_DETMATH_HIDDEN const double ATAN_TAB[130];

/* ------------------------------------------------------------------------------------------------- constants */
static const double EXP_INVL = 0x1.71547652b82fep+6; /* 64/ln2 */
static const double EXP_L1 = 0x1.62e42fefa0000p-7;   /* ln2/64, 36 bits: k L1 exact for |k| < 2^17 */
static const double EXP_L2 = 0x1.cf79abc9e3b3ap-46;  /* ln2/64 - L1 */
static const double LN2_HI = 0x1.62e42fefa3800p-1;   /* ln2, 42 bits: e LN2_HI exact for |e| < 2^11 */
static const double LN2_LO = 0x1.ef35793c76730p-45;  /* ln2 - LN2_HI */
static const double INV_PIO2 = 0x1.45f306dc9c883p-1; /* 2/pi */
static const double PIO2_1 = 0x1.921fb54400000p+0;   /* pi/2 = P1 + P2 + P3 + P4: 33-bit parts, k Pn exact */
static const double PIO2_2 = 0x1.0b4611a600000p-34;  /*   for |k| < 2^20 */
static const double PIO2_3 = 0x1.3198a2e000000p-69;
static const double PIO2_4 = 0x1.b839a252049c1p-104;
static const double PIO2_HI = 0x1.921fb54442d18p+0, PIO2_LO = 0x1.1a62633145c07p-54;
static const double PI_HI = 0x1.921fb54442d18p+1, PI_LO = 0x1.1a62633145c07p-53;
static const double PIO4 = 0x1.921fb54442d18p-1, PI3O4 = 0x1.2d97c7f3321d2p+1; /* nearest to pi/4, 3pi/4 */
static const double LNSQRT2PI_HI = 0x1.d67f1c864beb5p-1, LNSQRT2PI_LO = -0x1.65b5a1b7ff5dfp-55;

#endif
