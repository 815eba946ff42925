//! # Four f64 lanes
//!
//! The operations of the four-pose wrench-closure decision on four f64 lanes, written once
//! over [`F64x4`] and run on two builds with the same bits: [`Portable`] (`[f64; 4]`, lane by
//! lane, any CPU) and [`Avx`] (one `__m256d` register, `std::arch` AVX2 intrinsics, only
//! inside functions compiled with AVX2 after run-time detection). Every operation is exact
//! IEEE arithmetic of the same operands (no fused multiply–add), a comparison gives a mask
//! (all-ones or all-zeros bits per lane) with the meaning of Rust's operator on f64 (`!=` is
//! true for NaN, the others false), and a blend picks bits: the two builds agree bit for bit.
//!
//! ## References
//! - Intel 64 and IA-32 Architectures Software Developer's Manual, Vol. 2 (`VCMPPD`
//!   predicates, `VBLENDVPD`, `VPCMPGTQ`).

use super::{LANES, Lanes};

/// Four f64 lanes (values or masks).
pub(super) trait F64x4: Copy {
    /// Every lane `v`.
    fn splat(v: f64) -> Self;
    /// The lanes of `v`.
    fn load(v: &Lanes) -> Self;
    /// The lanes as an array.
    fn lanes(self) -> Lanes;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    fn div(self, o: Self) -> Self;
    /// `self > o` (false for NaN).
    fn gt(self, o: Self) -> Self;
    /// `self < o` (false for NaN).
    fn lt(self, o: Self) -> Self;
    /// `self <= o` (false for NaN).
    fn le(self, o: Self) -> Self;
    /// `self == o` (false for NaN).
    fn eq(self, o: Self) -> Self;
    /// `self != o` (true for NaN).
    fn ne(self, o: Self) -> Self;
    /// Bitwise and.
    fn and(self, o: Self) -> Self;
    /// Bitwise or.
    fn or(self, o: Self) -> Self;
    /// Bitwise xor.
    fn xor(self, o: Self) -> Self;
    /// `!self & o`, bitwise.
    fn and_not(self, o: Self) -> Self;
    /// `a` where the mask `m` is all ones, `b` where it is all zeros.
    fn blend(m: Self, a: Self, b: Self) -> Self;
    /// The bits as signed integers compared, `self < o` (a mask).
    fn int_lt(self, o: Self) -> Self;

    /// |self| (sign bit cleared).
    #[inline(always)]
    fn abs(self) -> Self {
        Self::splat(-0.0).and_not(self)
    }
    /// −self (sign bit flipped).
    #[inline(always)]
    fn neg(self) -> Self {
        self.xor(Self::splat(-0.0))
    }
    /// The bitwise complement (of a mask).
    #[inline(always)]
    fn not(self) -> Self {
        self.xor(Self::splat(f64::from_bits(u64::MAX)))
    }
    /// Whether each lane of a mask is set.
    #[inline(always)]
    fn is_set(self) -> [bool; LANES] {
        let v = self.lanes();
        [
            v[0].to_bits() != 0,
            v[1].to_bits() != 0,
            v[2].to_bits() != 0,
            v[3].to_bits() != 0,
        ]
    }
}

/// `[f64; 4]` lane by lane (any CPU).
#[derive(Clone, Copy)]
pub(super) struct Portable(Lanes);

/// The all-ones word for `true`, zero for `false`, as f64 bits.
#[inline(always)]
fn mask(b: bool) -> f64 {
    f64::from_bits(0u64.wrapping_sub(u64::from(b)))
}

impl Portable {
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self(std::array::from_fn(|l| f(self.0[l], o.0[l])))
    }
    #[inline(always)]
    fn bits2(self, o: Self, f: impl Fn(u64, u64) -> u64) -> Self {
        self.map2(o, |a, b| f64::from_bits(f(a.to_bits(), b.to_bits())))
    }
}

impl F64x4 for Portable {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        Self([v; LANES])
    }
    #[inline(always)]
    fn load(v: &Lanes) -> Self {
        Self(*v)
    }
    #[inline(always)]
    fn lanes(self) -> Lanes {
        self.0
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.map2(o, |a, b| a + b)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.map2(o, |a, b| a - b)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.map2(o, |a, b| a * b)
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.map2(o, |a, b| a / b)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        self.map2(o, |a, b| mask(a > b))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        self.map2(o, |a, b| mask(a < b))
    }
    #[inline(always)]
    fn le(self, o: Self) -> Self {
        self.map2(o, |a, b| mask(a <= b))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> Self {
        self.map2(o, |a, b| mask(a == b))
    }
    #[inline(always)]
    fn ne(self, o: Self) -> Self {
        self.map2(o, |a, b| mask(a != b))
    }
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        self.bits2(o, |a, b| a & b)
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        self.bits2(o, |a, b| a | b)
    }
    #[inline(always)]
    fn xor(self, o: Self) -> Self {
        self.bits2(o, |a, b| a ^ b)
    }
    #[inline(always)]
    fn and_not(self, o: Self) -> Self {
        self.bits2(o, |a, b| !a & b)
    }
    #[inline(always)]
    fn blend(m: Self, a: Self, b: Self) -> Self {
        m.and(a).or(m.and_not(b))
    }
    #[inline(always)]
    fn int_lt(self, o: Self) -> Self {
        self.map2(o, |a, b| mask((a.to_bits() as i64) < (b.to_bits() as i64)))
    }
}

#[cfg(target_arch = "x86_64")]
pub(super) use avx::Avx;

#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{F64x4, Lanes};
    use std::arch::x86_64::*;

    /// One AVX2 register. Its operations may only run inside a function compiled with
    /// `#[target_feature(enable = "avx2")]`, called after run-time detection of AVX2 (they
    /// are inlined there).
    #[derive(Clone, Copy)]
    pub(in crate::wrench_closure) struct Avx(__m256d);

    // SAFETY (every `unsafe` block below): the intrinsics need AVX (AVX2 for
    // `_mm256_cmpgt_epi64`); `Avx` values exist only inside `decide_lanes_avx2`, which runs
    // on CPUs with AVX2 (run-time detection in `WrenchClosureTest::new`). Loads and stores go
    // through `Lanes` references (32 bytes, unaligned access).
    impl F64x4 for Avx {
        #[inline(always)]
        fn splat(v: f64) -> Self {
            Self(unsafe { _mm256_set1_pd(v) })
        }
        #[inline(always)]
        fn load(v: &Lanes) -> Self {
            Self(unsafe { _mm256_loadu_pd(v.as_ptr()) })
        }
        #[inline(always)]
        fn lanes(self) -> Lanes {
            let mut out = [0.0; 4];
            unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
            out
        }
        #[inline(always)]
        fn add(self, o: Self) -> Self {
            Self(unsafe { _mm256_add_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            Self(unsafe { _mm256_sub_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            Self(unsafe { _mm256_mul_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn div(self, o: Self) -> Self {
            Self(unsafe { _mm256_div_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn gt(self, o: Self) -> Self {
            Self(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn lt(self, o: Self) -> Self {
            Self(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn le(self, o: Self) -> Self {
            Self(unsafe { _mm256_cmp_pd::<_CMP_LE_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn eq(self, o: Self) -> Self {
            Self(unsafe { _mm256_cmp_pd::<_CMP_EQ_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn ne(self, o: Self) -> Self {
            Self(unsafe { _mm256_cmp_pd::<_CMP_NEQ_UQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn and(self, o: Self) -> Self {
            Self(unsafe { _mm256_and_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn or(self, o: Self) -> Self {
            Self(unsafe { _mm256_or_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn xor(self, o: Self) -> Self {
            Self(unsafe { _mm256_xor_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn and_not(self, o: Self) -> Self {
            Self(unsafe { _mm256_andnot_pd(self.0, o.0) })
        }
        #[inline(always)]
        fn blend(m: Self, a: Self, b: Self) -> Self {
            // `blendv` takes `a` where the sign bit of `m` is set (masks are all ones or zeros).
            Self(unsafe { _mm256_blendv_pd(b.0, a.0, m.0) })
        }
        #[inline(always)]
        fn int_lt(self, o: Self) -> Self {
            Self(unsafe {
                _mm256_castsi256_pd(_mm256_cmpgt_epi64(
                    _mm256_castpd_si256(o.0),
                    _mm256_castpd_si256(self.0),
                ))
            })
        }
    }
}
