//! # Four f64 lanes (SIMD)
//!
//! [`F64x4`] is the handful of lane-wise operations a fixed-size kernel needs (arithmetic, the
//! comparisons and selects that replace branches, a few bit operations), with two
//! implementations that give the same bits: [`Portable`] (plain arrays, any target) and, on
//! x86-64, [`Avx2`] (one AVX2 instruction, or two, per operation, obtained only after run-time
//! detection). A kernel written once against [`F64x4`] runs four problems at a time; each lane
//! performs the floating-point operations of the scalar code in the same order (no fused
//! multiply–adds: Rust never forms them, and the trait has none), so each lane's result is the
//! scalar result bit for bit. The kernels of the stack that use it: the planar closed form
//! (`cdpr_tension::closed_form::PlanarClosedForm::is_feasible_lanes`), the dextrous workspace
//! slices (`cdpr_workspace::dextrous`) and the four-pose wrench-closure decision
//! (`cdpr_workspace::wrench_closure`).
//!
//! **Semantics that matter for bit-identity.**
//! - Arithmetic (`add`, `sub`, `mul`, `div`, `sqrt`) is IEEE binary64, round to nearest,
//!   exactly Rust's operators on each lane (a NaN result is some quiet NaN: its sign and payload
//!   are not specified, as in Rust).
//! - [`F64x4::abs`], [`F64x4::neg`] and [`F64x4::neg_where`] touch only the sign bit (so
//!   −0 ↔ +0 and NaN keeps its payload), as `f64::abs` and unary `-`.
//! - Comparisons are IEEE ordered ones (false when an operand is NaN) except [`F64x4::ne`]
//!   (true when an operand is NaN), as Rust's `<`, `==` and `!=`; −0 == +0.
//!   [`F64x4::lt_bits`] compares the bit patterns as signed 64-bit integers instead (the
//!   order of `f64::total_cmp` on non-negative values, and −0 below every one of them).
//! - [`F64x4::max`] is `if a > b { a } else { b }` (the second operand when either is NaN, as
//!   `maxpd`; max(−0, +0) = +0 and max(+0, −0) = −0), which equals Rust's `f64::max` whenever
//!   the first operand is not NaN and the two are not zeros of different signs;
//!   [`F64x4::min`] likewise `if a < b { a } else { b }` (`minpd`), Rust's `f64::min` under the
//!   same conditions (so `x.min(1.0)` of a possibly NaN `x` is `f64::min(x, 1.0)` exactly).
//! - A select ([`F64x4::select`], [`F64x4::keep`]) copies the bits of the operand it picks;
//!   `keep` gives +0 (all bits zero) in the lanes it drops, so `e − x.keep(m)` is `e` bit for
//!   bit where `m` is false (e − (+0) = e, −0 included).
//! - A [`F64x4::Mask`] is lane-wise booleans, built only by the comparisons,
//!   [`F64x4::mask`] and the logic on masks (`and`, `or`, `xor`, `and_not`, `not`); its
//!   representation is the implementation's (`[bool; 4]`, or an all-ones / all-zeros
//!   64-bit pattern per lane in an AVX2 register) and never mixes with values.
//!
//! A value of [`Avx2`] exists only when the CPU supports AVX2 ([`Avx2::detect`], or
//! [`Avx2::new_unchecked`] inside code that may already assume it); every new value is made
//! from an existing one ([`F64x4::splat`], [`F64x4::load`]), which is the proof that the
//! instructions are available. Kernels reach full speed when they are inlined into a function
//! compiled with `#[target_feature(enable = "avx2")]`: every operation is
//! `#[inline(always)]`, and a kernel must not call closures (`array::map`, `from_fn`), which
//! are compiled without the caller's target features and turn every intrinsic into a call.
//!
//! ## References
//! - Intel 64 and IA-32 Architectures Software Developer's Manual, vol. 2 (`MAXPD`, `CMPPD`
//!   predicates, `BLENDVPD`, `PCMPGTQ`, `MOVMSKPD`).

/// Four f64 lanes and their masks (see the module docs for the exact semantics).
pub trait F64x4: Copy {
    /// Lane-wise booleans.
    type Mask: Copy;
    /// Every lane `v` (`self` only witnesses that the lanes' instructions are available).
    fn splat(self, v: f64) -> Self;
    /// The lanes `a[0..4]` (`self` is the witness).
    fn load(self, a: [f64; 4]) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [f64; 4];
    /// `self + o` lane by lane.
    fn add(self, o: Self) -> Self;
    /// `self − o`.
    fn sub(self, o: Self) -> Self;
    /// `self · o`.
    fn mul(self, o: Self) -> Self;
    /// `self / o`.
    fn div(self, o: Self) -> Self;
    /// √self (IEEE, correctly rounded).
    fn sqrt(self) -> Self;
    /// |self| (the sign bit cleared).
    fn abs(self) -> Self;
    /// −self (the sign bit flipped).
    fn neg(self) -> Self;
    /// `if self > o { self } else { o }` (`o` when either is NaN).
    fn max(self, o: Self) -> Self;
    /// `if self < o { self } else { o }` (`o` when either is NaN).
    fn min(self, o: Self) -> Self;
    /// `self > o` (false for NaN).
    fn gt(self, o: Self) -> Self::Mask;
    /// `self ≥ o` (false for NaN).
    fn ge(self, o: Self) -> Self::Mask;
    /// `self < o` (false for NaN).
    fn lt(self, o: Self) -> Self::Mask;
    /// `self ≤ o` (false for NaN).
    fn le(self, o: Self) -> Self::Mask;
    /// `self == o` (false for NaN).
    fn eq(self, o: Self) -> Self::Mask;
    /// `self != o` (true for NaN).
    fn ne(self, o: Self) -> Self::Mask;
    /// `(self.to_bits() as i64) < (o.to_bits() as i64)`: the bit patterns compared as signed
    /// integers.
    fn lt_bits(self, o: Self) -> Self::Mask;
    /// `if m { a } else { b }` lane by lane.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `if m { self } else { +0.0 }` lane by lane.
    fn keep(self, m: Self::Mask) -> Self;
    /// `if m { −self } else { self }` lane by lane (the sign bit flipped where `m`).
    fn neg_where(self, m: Self::Mask) -> Self;
    /// Every lane `b` (`self` is the witness).
    fn mask(self, b: bool) -> Self::Mask;
    /// `a && b`.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `a || b`.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `a && !b`.
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `a != b` (exclusive or).
    fn xor(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `!m`.
    fn not(m: Self::Mask) -> Self::Mask;
    /// Bit l set when lane l is true.
    fn bits(m: Self::Mask) -> u32;
    /// The lanes of a mask as booleans.
    #[inline(always)]
    fn to_bools(m: Self::Mask) -> [bool; 4] {
        let b = Self::bits(m);
        [b & 1 != 0, b & 2 != 0, b & 4 != 0, b & 8 != 0]
    }
}

/// [`F64x4`] on plain arrays (any target; the compiler may vectorise it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Portable(pub [f64; 4]);

impl Portable {
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Self(self.0.map(f))
    }
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self(std::array::from_fn(|l| f(self.0[l], o.0[l])))
    }
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(f64, f64) -> bool) -> [bool; 4] {
        std::array::from_fn(|l| f(self.0[l], o.0[l]))
    }
}

impl F64x4 for Portable {
    type Mask = [bool; 4];
    #[inline(always)]
    fn splat(self, v: f64) -> Self {
        Self([v; 4])
    }
    #[inline(always)]
    fn load(self, a: [f64; 4]) -> Self {
        Self(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        self.0
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.zip(o, |a, b| a + b)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.zip(o, |a, b| a - b)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.zip(o, |a, b| a * b)
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.zip(o, |a, b| a / b)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f64::abs)
    }
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.zip(o, |a, b| if a > b { a } else { b })
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.zip(o, |a, b| if a < b { a } else { b })
    }
    #[inline(always)]
    fn gt(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a > b)
    }
    #[inline(always)]
    fn ge(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a >= b)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a == b)
    }
    #[inline(always)]
    fn ne(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| a != b)
    }
    #[inline(always)]
    fn lt_bits(self, o: Self) -> [bool; 4] {
        self.test(o, |a, b| (a.to_bits() as i64) < (b.to_bits() as i64))
    }
    #[inline(always)]
    fn select(m: [bool; 4], a: Self, b: Self) -> Self {
        Self(std::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
    #[inline(always)]
    fn keep(self, m: [bool; 4]) -> Self {
        Self(std::array::from_fn(|l| if m[l] { self.0[l] } else { 0.0 }))
    }
    #[inline(always)]
    fn neg_where(self, m: [bool; 4]) -> Self {
        Self(std::array::from_fn(|l| {
            if m[l] { -self.0[l] } else { self.0[l] }
        }))
    }
    #[inline(always)]
    fn mask(self, b: bool) -> [bool; 4] {
        [b; 4]
    }
    #[inline(always)]
    fn and(a: [bool; 4], b: [bool; 4]) -> [bool; 4] {
        std::array::from_fn(|l| a[l] & b[l])
    }
    #[inline(always)]
    fn or(a: [bool; 4], b: [bool; 4]) -> [bool; 4] {
        std::array::from_fn(|l| a[l] | b[l])
    }
    #[inline(always)]
    fn and_not(a: [bool; 4], b: [bool; 4]) -> [bool; 4] {
        std::array::from_fn(|l| a[l] & !b[l])
    }
    #[inline(always)]
    fn xor(a: [bool; 4], b: [bool; 4]) -> [bool; 4] {
        std::array::from_fn(|l| a[l] ^ b[l])
    }
    #[inline(always)]
    fn not(m: [bool; 4]) -> [bool; 4] {
        m.map(|b| !b)
    }
    #[inline(always)]
    fn bits(m: [bool; 4]) -> u32 {
        (m[0] as u32) | (m[1] as u32) << 1 | (m[2] as u32) << 2 | (m[3] as u32) << 3
    }
}

#[cfg(target_arch = "x86_64")]
pub use avx2::Avx2;

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::F64x4;
    use std::arch::x86_64::*;

    /// [`F64x4`] in one AVX2 register. A value exists only on a CPU with AVX2
    /// ([`Avx2::detect`]), which makes its safe methods sound.
    #[derive(Debug, Clone, Copy)]
    pub struct Avx2(__m256d);

    impl Avx2 {
        /// Zero lanes, if the CPU supports AVX2 (run-time detection, cached by the standard
        /// library).
        pub fn detect() -> Option<Self> {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: AVX2 (hence AVX) is available.
                Some(Self(unsafe { _mm256_setzero_pd() }))
            } else {
                None
            }
        }

        /// The witness without detection, for code whose own safety contract already
        /// requires AVX2 (a `#[target_feature(enable = "avx2")]` function).
        ///
        /// # Safety
        /// The CPU must support AVX2.
        #[inline(always)]
        pub unsafe fn new_unchecked() -> Self {
            // SAFETY: AVX is available (the caller's contract).
            Self(unsafe { _mm256_setzero_pd() })
        }
    }

    // SAFETY (every `unsafe` block below): an `Avx2` value exists only when the CPU supports
    // AVX2 (`Avx2::detect`), and every method has one (`self` or a mask made by one).
    macro_rules! op {
        ($name:ident, $intr:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> Self {
                Self(unsafe { $intr(self.0, o.0) })
            }
        };
    }
    macro_rules! cmp {
        ($name:ident, $pred:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> __m256d {
                unsafe { _mm256_cmp_pd::<$pred>(self.0, o.0) }
            }
        };
    }

    macro_rules! logic {
        ($name:ident, $intr:ident) => {
            #[inline(always)]
            fn $name(a: __m256d, b: __m256d) -> __m256d {
                unsafe { $intr(a, b) }
            }
        };
    }

    impl F64x4 for Avx2 {
        type Mask = __m256d;
        #[inline(always)]
        fn splat(self, v: f64) -> Self {
            Self(unsafe { _mm256_set1_pd(v) })
        }
        #[inline(always)]
        fn load(self, a: [f64; 4]) -> Self {
            Self(unsafe { _mm256_loadu_pd(a.as_ptr()) })
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            let mut a = [0.0; 4];
            unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
            a
        }
        op!(add, _mm256_add_pd);
        op!(sub, _mm256_sub_pd);
        op!(mul, _mm256_mul_pd);
        op!(div, _mm256_div_pd);
        op!(max, _mm256_max_pd);
        op!(min, _mm256_min_pd);
        #[inline(always)]
        fn sqrt(self) -> Self {
            Self(unsafe { _mm256_sqrt_pd(self.0) })
        }
        #[inline(always)]
        fn abs(self) -> Self {
            Self(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
        }
        #[inline(always)]
        fn neg(self) -> Self {
            Self(unsafe { _mm256_xor_pd(_mm256_set1_pd(-0.0), self.0) })
        }
        cmp!(gt, _CMP_GT_OQ);
        cmp!(ge, _CMP_GE_OQ);
        cmp!(lt, _CMP_LT_OQ);
        cmp!(le, _CMP_LE_OQ);
        cmp!(eq, _CMP_EQ_OQ);
        cmp!(ne, _CMP_NEQ_UQ);
        #[inline(always)]
        fn lt_bits(self, o: Self) -> __m256d {
            unsafe {
                _mm256_castsi256_pd(_mm256_cmpgt_epi64(
                    _mm256_castpd_si256(o.0),
                    _mm256_castpd_si256(self.0),
                ))
            }
        }
        #[inline(always)]
        fn select(m: __m256d, a: Self, b: Self) -> Self {
            // `blendv` takes `a` where the sign bit of `m` is set (masks are all ones or zeros).
            Self(unsafe { _mm256_blendv_pd(b.0, a.0, m) })
        }
        #[inline(always)]
        fn keep(self, m: __m256d) -> Self {
            Self(unsafe { _mm256_and_pd(self.0, m) })
        }
        #[inline(always)]
        fn neg_where(self, m: __m256d) -> Self {
            Self(unsafe { _mm256_xor_pd(self.0, _mm256_and_pd(m, _mm256_set1_pd(-0.0))) })
        }
        #[inline(always)]
        fn mask(self, b: bool) -> __m256d {
            unsafe { _mm256_set1_pd(f64::from_bits(0u64.wrapping_sub(u64::from(b)))) }
        }
        logic!(and, _mm256_and_pd);
        logic!(or, _mm256_or_pd);
        logic!(xor, _mm256_xor_pd);
        #[inline(always)]
        fn and_not(a: __m256d, b: __m256d) -> __m256d {
            unsafe { _mm256_andnot_pd(b, a) }
        }
        #[inline(always)]
        fn not(m: __m256d) -> __m256d {
            unsafe { _mm256_xor_pd(m, _mm256_set1_pd(f64::from_bits(u64::MAX))) }
        }
        #[inline(always)]
        fn bits(m: __m256d) -> u32 {
            (unsafe { _mm256_movemask_pd(m) }) as u32
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Special values for the lane-by-lane comparison of the two implementations.
    const VALUES: [f64; 12] = [
        0.0,
        -0.0,
        1.0,
        -2.5,
        1e-300,
        3.0e300,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        0.1,
        -7.0,
        2.0,
    ];

    /// Every operation of [`Avx2`] gives [`Portable`]'s bits (NaN compared as NaN), and
    /// [`Portable`] gives the scalar expressions' (`max` as `if a > b { a } else { b }`, `min`
    /// as `f64::min(x, 1.0)` where the second operand is 1, `keep`
    /// +0 in the dropped lanes, `neg_where` the sign bit flipped), on signed zeros, infinities,
    /// NaN and extreme magnitudes.
    #[test]
    fn avx2_matches_portable_matches_scalar() {
        let same = |a: [f64; 4], b: [f64; 4]| {
            a.iter()
                .zip(&b)
                .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
        };
        let p = Portable([0.0; 4]);
        for i in 0..VALUES.len() {
            let a: [f64; 4] = std::array::from_fn(|l| VALUES[(i + l) % VALUES.len()]);
            let b: [f64; 4] = std::array::from_fn(|l| VALUES[(i * 5 + 3 * l + 1) % VALUES.len()]);
            let (pa, pb) = (p.load(a), p.load(b));
            let scalar =
                |f: fn(f64, f64) -> f64| -> [f64; 4] { std::array::from_fn(|l| f(a[l], b[l])) };
            assert!(same(pa.add(pb).0, scalar(|x, y| x + y)));
            assert!(same(pa.div(pb).0, scalar(|x, y| x / y)));
            assert!(same(pa.max(pb).0, scalar(|x, y| if x > y { x } else { y })));
            assert!(same(pa.min(pb).0, scalar(|x, y| if x < y { x } else { y })));
            let one = p.splat(1.0);
            assert!(same(pa.min(one).0, a.map(|x| x.min(1.0))));
            assert!(same(pa.sqrt().0, a.map(f64::sqrt)));
            assert_eq!(
                Portable::bits(pa.ne(pb)),
                (0..4).map(|l| ((a[l] != b[l]) as u32) << l).sum::<u32>()
            );
            let lt_bits: [bool; 4] =
                std::array::from_fn(|l| (a[l].to_bits() as i64) < (b[l].to_bits() as i64));
            assert_eq!(Portable::to_bools(pa.lt_bits(pb)), lt_bits);
            let m = pa.lt(pb);
            let kept: [f64; 4] = std::array::from_fn(|l| if a[l] < b[l] { b[l] } else { 0.0 });
            assert!(same(pb.keep(m).0, kept));
            let negated: [f64; 4] = std::array::from_fn(|l| if a[l] < b[l] { -b[l] } else { b[l] });
            let bits = |v: [f64; 4]| v.map(f64::to_bits);
            assert_eq!(bits(pb.neg_where(m).0), bits(negated));
            assert_eq!(Portable::to_bools(p.mask(true)), [true; 4]);
            assert_eq!(Portable::to_bools(p.mask(false)), [false; 4]);
            assert_eq!(
                Portable::to_bools(Portable::not(m)),
                std::array::from_fn(|l| a[l] >= b[l] || a[l].is_nan() || b[l].is_nan())
            );
            #[cfg(target_arch = "x86_64")]
            if let Some(v) = Avx2::detect() {
                let (va, vb) = (v.load(a), v.load(b));
                let (m, q) = (va.lt(vb), pa.lt(pb));
                let pairs: [(Avx2, Portable); 12] = [
                    (va.add(vb), pa.add(pb)),
                    (va.sub(vb), pa.sub(pb)),
                    (va.mul(vb), pa.mul(pb)),
                    (va.div(vb), pa.div(pb)),
                    (va.max(vb), pa.max(pb)),
                    (va.min(vb), pa.min(pb)),
                    (va.sqrt(), pa.sqrt()),
                    (va.abs(), pa.abs()),
                    (va.neg(), pa.neg()),
                    (
                        Avx2::select(va.lt(vb), va, vb),
                        Portable::select(pa.lt(pb), pa, pb),
                    ),
                    (vb.keep(m), pb.keep(q)),
                    (vb.neg_where(m), pb.neg_where(q)),
                ];
                for (k, (x, y)) in pairs.iter().enumerate() {
                    assert!(same(x.to_array(), y.0), "op {k}: {a:?} {b:?}");
                }
                let (m1, m2) = (va.lt(vb), va.eq(va));
                let (q1, q2) = (pa.lt(pb), pa.eq(pa));
                let masks = [
                    (va.gt(vb), pa.gt(pb)),
                    (va.ge(vb), pa.ge(pb)),
                    (va.lt(vb), pa.lt(pb)),
                    (va.le(vb), pa.le(pb)),
                    (va.eq(vb), pa.eq(pb)),
                    (va.ne(vb), pa.ne(pb)),
                    (va.lt_bits(vb), pa.lt_bits(pb)),
                    (v.mask(true), p.mask(true)),
                    (v.mask(false), p.mask(false)),
                    (Avx2::not(m), Portable::not(q)),
                    (Avx2::and(m1, m2), Portable::and(q1, q2)),
                    (Avx2::or(m1, m2), Portable::or(q1, q2)),
                    (Avx2::and_not(m2, m1), Portable::and_not(q2, q1)),
                    (Avx2::xor(m1, m2), Portable::xor(q1, q2)),
                ];
                for (k, (x, y)) in masks.iter().enumerate() {
                    assert_eq!(Avx2::bits(*x), Portable::bits(*y), "mask {k}: {a:?} {b:?}");
                }
                assert_eq!(Avx2::to_bools(m1), Portable::to_bools(q1));
            }
        }
    }
}
