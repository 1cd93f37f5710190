//! A quantity given as a time table: driver inputs, steering and brake demands over time.

use crate::error::{require_finite, Error, Result};
use crate::math::Real;

/// A quantity given as a time table, linear between its points and held beyond its ends.
/// As a document: rows of [time s, value], read back through [`Table::new`]'s checks.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "Vec<[Real; 2]>", into = "Vec<[Real; 2]>")
)]
pub struct Table {
    times: Vec<Real>,
    values: Vec<Real>,
}

impl Table {
    /// A table from (time s, value) points: at least one, every number finite, times strictly
    /// increasing. `what` names the quantity in errors.
    pub fn new(what: &str, points: &[(Real, Real)]) -> Result<Table> {
        if points.is_empty() {
            return Err(Error::invalid(format!(
                "the {what} table is empty: give at least one (time, value) point"
            )));
        }
        for (k, &(t, v)) in points.iter().enumerate() {
            require_finite(&format!("{what} table time at row {k}"), t)?;
            require_finite(&format!("{what} table value at row {k}"), v)?;
            if k > 0 && t <= points[k - 1].0 {
                return Err(Error::invalid(format!(
                    "the {what} table's times must increase: row {k} has t = {t} s after \
                     t = {} s (sort the rows and drop duplicates)",
                    points[k - 1].0
                )));
            }
        }
        Ok(Table {
            times: points.iter().map(|p| p.0).collect(),
            values: points.iter().map(|p| p.1).collect(),
        })
    }

    /// A constant.
    pub fn constant(value: Real) -> Table {
        Table {
            times: vec![0.0],
            values: vec![value],
        }
    }

    /// The value at time `t` (s): linear between points, held beyond the ends.
    pub fn at(&self, t: Real) -> Real {
        // Beyond the ends v1 = v0 and the fraction 0: v0 itself.
        let (v0, v1, fraction) = self.segment(t);
        v0 + (v1 - v0) * fraction
    }

    /// The values at the points before and after time `t` (s) and how far between them `t`
    /// lies, in [0, 1): `at(t)` is the first plus the fraction of the difference. Beyond
    /// the ends: the end's value twice and 0.
    pub fn segment(&self, t: Real) -> (Real, Real, Real) {
        let n = self.times.len();
        if t <= self.times[0] {
            return (self.values[0], self.values[0], 0.0);
        }
        if t >= self.times[n - 1] {
            return (self.values[n - 1], self.values[n - 1], 0.0);
        }
        // The last point at or before t (times increase, so the search is exact).
        let k = self.times.partition_point(|&x| x <= t) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        (self.values[k], self.values[k + 1], (t - t0) / (t1 - t0))
    }

    /// Smallest and largest value.
    pub fn range(&self) -> (Real, Real) {
        let lo = self.values.iter().copied().fold(Real::INFINITY, Real::min);
        let hi = self
            .values
            .iter()
            .copied()
            .fold(Real::NEG_INFINITY, Real::max);
        (lo, hi)
    }

    /// The points (time s, value).
    pub fn points(&self) -> impl Iterator<Item = (Real, Real)> + '_ {
        self.times.iter().copied().zip(self.values.iter().copied())
    }
}

impl TryFrom<Vec<[Real; 2]>> for Table {
    type Error = Error;
    fn try_from(rows: Vec<[Real; 2]>) -> Result<Table> {
        let points: Vec<(Real, Real)> = rows.iter().map(|r| (r[0], r[1])).collect();
        Table::new("document's", &points)
    }
}

impl From<Table> for Vec<[Real; 2]> {
    fn from(t: Table) -> Self {
        t.points().map(|(a, b)| [a, b]).collect()
    }
}
