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

/// [`bisect`] on the grid of whole multiples of `grid` (s, a power of two): `lo` rounded
/// down and `hi` up to it (`holds` taken false at the one, checked at the other), then halved
/// down to one grid step. For a `holds` that turns true once, the answer is the first grid
/// point where it holds whatever bracket the search began from: two searches that closed in
/// on the same instant from different sides (a scene and its mirror image, whose triangles
/// come in another order) land on the same bits. When `holds` fails at the rounded-up end,
/// the grid point below `hi` is tried, and failing both the plain [`bisect`] to one grid step
/// is returned.
pub fn bisect_on_grid(lo: Real, hi: Real, grid: Real, mut holds: impl FnMut(Real) -> bool) -> Real {
    let mut a = (lo / grid).floor();
    let mut b = (hi / grid).ceil();
    if b * grid != hi && !holds(b * grid) {
        if b - 1.0 > a && holds((b - 1.0) * grid) {
            b -= 1.0;
        } else {
            return bisect(lo, hi, grid, holds);
        }
    }
    // Whole numbers below 2^53 as floats: the midpoints are exact.
    while b - a > 1.0 {
        let mid = (0.5 * (a + b)).floor();
        if holds(mid * grid) {
            b = mid;
        } else {
            a = mid;
        }
    }
    b * grid
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_a_grid_the_answer_does_not_depend_on_the_bracket() {
        let grid = (2.0 as Real).powi(-30);
        let threshold = 3.7e-4;
        let first = bisect_on_grid(0.0, 1e-3, grid, |t| t >= threshold);
        assert!(first >= threshold && first - grid < threshold);
        for (lo, hi) in [
            (1e-5, 4e-4),
            (3.6e-4, 3.71e-4),
            (2e-4, 9e-4),
            (3.699e-4, 3.7e-4),
        ] {
            assert_eq!(bisect_on_grid(lo, hi, grid, |t| t >= threshold), first);
        }
    }

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
