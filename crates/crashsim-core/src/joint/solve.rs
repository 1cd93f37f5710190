//! The joints' linear system: `(J W J^T) lambda = rhs` over the rows of constraint.rs, W the
//! bodies' inverse masses and world inverse inertias. Symmetric positive definite for a tree
//! of joints (Cholesky); redundant rows (a loop, a body held twice) by least squares.

use nalgebra::{DMatrix, DVector};

use super::constraint::{JointBody, Row};
use crate::math::{Real, Vector};

/// W J^T for one row: the (linear, angular) velocity change of body a and body b per unit
/// of the row's impulse.
pub(super) fn mobility(row: &Row, bodies: &[JointBody]) -> ([Vector; 2], [Vector; 2]) {
    let a = &bodies[row.a];
    let da = [row.ja[0] * a.inv_mass, a.inv_inertia * row.ja[1]];
    let db = match row.b {
        Some(b) => [
            row.jb[0] * bodies[b].inv_mass,
            bodies[b].inv_inertia * row.jb[1],
        ],
        None => [Vector::zeros(); 2],
    };
    (da, db)
}

/// Solves `(J W J^T) lambda = rhs` for the rows.
pub(super) fn solve(rows: &[Row], bodies: &[JointBody], rhs: DVector<Real>) -> DVector<Real> {
    let n = rows.len();
    let moves: Vec<_> = rows.iter().map(|r| mobility(r, bodies)).collect();
    let mut a = DMatrix::<Real>::zeros(n, n);
    for i in 0..n {
        for j in i..n {
            let (ri, rj) = (&rows[i], &rows[j]);
            let (ma, mb) = &moves[j];
            let mut s = 0.0;
            // Row i's J on every body row j moves.
            for (body, m) in [(Some(rj.a), ma), (rj.b, mb)] {
                let Some(body) = body else { continue };
                if ri.a == body {
                    s += ri.ja[0].dot(&m[0]) + ri.ja[1].dot(&m[1]);
                }
                if ri.b == Some(body) {
                    s += ri.jb[0].dot(&m[0]) + ri.jb[1].dot(&m[1]);
                }
            }
            a[(i, j)] = s;
            a[(j, i)] = s;
        }
    }
    if let Some(chol) = a.clone().cholesky() {
        return chol.solve(&rhs);
    }
    // Redundant rows: the least-squares reactions (the solve cannot fail for an SVD).
    a.svd(true, true)
        .solve(&rhs, 1e-12)
        .unwrap_or_else(|_| DVector::zeros(n))
}
