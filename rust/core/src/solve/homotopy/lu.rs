//! Complex Gaussian elimination for the tracker's small square systems, at sizes known to
//! the compiler where it can.

use super::C;

/// Solves the m x m system in place by Gaussian elimination with partial pivoting (row
/// major `a`); the solution replaces `b`. False on a zero or non-finite pivot.
pub(super) fn lu_solve(a: &mut [C], m: usize, b: &mut [C]) -> bool {
    // the tracker's systems are (N + 1) square, N <= MAX_LINKS: the same elimination at a
    // size known to the compiler (constant loop bounds), bit for bit
    macro_rules! fixed {
        ($($n:literal)*) => {
            match m {
                $($n => return lu_fixed::<$n>(a, b),)*
                _ => {}
            }
        };
    }
    fixed!(2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17);
    lu_dynamic(a, m, b)
}

/// [`lu_solve`] for an M x M system: the same operations in the same order.
fn lu_fixed<const M: usize>(a: &mut [C], b: &mut [C]) -> bool {
    lu_dynamic(&mut a[..M * M], M, &mut b[..M])
}

#[inline(always)]
fn lu_dynamic(a: &mut [C], m: usize, b: &mut [C]) -> bool {
    for k in 0..m {
        let mut p = k;
        let mut best = a[k * m + k].norm_sqr();
        for i in k + 1..m {
            let v = a[i * m + k].norm_sqr();
            if v > best {
                best = v;
                p = i;
            }
        }
        if !(best > 0.0 && best.is_finite()) {
            return false;
        }
        if p != k {
            for c in 0..m {
                a.swap(k * m + c, p * m + c);
            }
            b.swap(k, p);
        }
        let inv = C::new(1.0, 0.0) / a[k * m + k];
        let bk = b[k];
        // rows below k minus f times row k (the same operations, on row slices)
        let (top, rest) = a.split_at_mut((k + 1) * m);
        let rk = &top[k * m + k + 1..(k + 1) * m];
        for (row, bi) in rest.chunks_exact_mut(m).zip(&mut b[k + 1..]) {
            let f = row[k] * inv;
            if f == C::default() {
                continue;
            }
            for (x, &v) in row[k + 1..].iter_mut().zip(rk) {
                *x -= f * v;
            }
            *bi -= f * bk;
        }
    }
    for k in (0..m).rev() {
        let mut s = b[k];
        for c in k + 1..m {
            s -= a[k * m + c] * b[c];
        }
        b[k] = s / a[k * m + k];
    }
    b.iter().all(|v| v.re.is_finite() && v.im.is_finite())
}
