//! One bisection for every instant the engine resolves inside a step (first overlap,
//! separation, closing again, the automatic depth of penetration).

use crate::math::Real;

/// The bracket's upper end after bisecting [lo, hi] on `holds` down to a width of at most
/// `tolerance`: `holds` is taken false at `lo` and true at `hi` (neither end is evaluated),
/// and the returned point is one where it held (or `hi` itself).
///
/// Bounded: the loop also ends when the midpoint no longer differs from an end (the bracket
/// is one float wide, e.g. a tolerance below the spacing of floats near `lo`), so it runs at
/// most about log2((hi - lo) / tolerance) + 1 times and never more than 1100 times.
pub fn bisect(
    mut lo: Real,
    mut hi: Real,
    tolerance: Real,
    mut holds: impl FnMut(Real) -> bool,
) -> Real {
    while hi - lo > tolerance {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_threshold_to_the_tolerance() {
        let t = bisect(0.0, 1.0, 1e-9, |x| x >= 0.3);
        assert!(t >= 0.3 && t - 0.3 <= 1e-9, "{t}");
    }

    #[test]
    fn a_tolerance_below_the_float_spacing_ends_instead_of_hanging() {
        // Near 1e8 floats are 1.5e-8 apart: a 1e-9 tolerance can never be met.
        let mut calls = 0;
        let t = bisect(1e8, 1e8 + 1.0, 1e-9, |x| {
            calls += 1;
            x >= 1e8 + 0.5
        });
        assert!((t - (1e8 + 0.5)).abs() <= 3e-8, "{t}");
        assert!(calls < 100, "{calls} evaluations");
    }
}
