//! The joints' linear system: `(J W J^T) lambda = rhs` over the rows of constraint.rs, W the
//! bodies' inverse masses and world inverse inertias. Symmetric positive definite for a tree
//! of joints (Cholesky); redundant rows (a loop, a body held twice) by least squares.
//!
//! Results are those of nalgebra's dense Cholesky of the rows in the order factored (their
//! own, or reversed: [`Symbolic::reversed`]) bit for bit (the tests compare them); only the
//! zeros of the matrix and of its factor are passed over.

use std::cell::RefCell;
use std::collections::HashMap;

use nalgebra::{DMatrix, DMatrixView, DVector};

use super::row::{JointBody, Row};
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

/// From this many rows on, the solve passes over the zeros ([`matrix`], [`factor`]); below
/// it the plain dense solve is as fast or faster. Measured on random trees of joints
/// (dense against sparse, us per solve): 5 rows 0.19 against 0.33, 26 rows 2.9 against 3.0,
/// 36 rows 5.3 against 4.9, 52 rows 11.6 against 9.6, 93 rows 53 against 44. Both give the
/// same bits.
const SPARSE_FROM_ROWS: usize = 30;

/// Solves `(J W J^T) lambda = rhs` for the rows.
pub(super) fn solve(rows: &[Row], bodies: &[JointBody], rhs: DVector<Real>) -> DVector<Real> {
    let mut x = solve_each(rows, bodies, vec![rhs]);
    x.pop().expect("one solution per right-hand side")
}

/// [`solve`] for several right-hand sides: the matrix built and factored once, each side
/// solved with that factor (each solution the bits [`solve`] gives it alone).
pub(super) fn solve_each(
    rows: &[Row],
    bodies: &[JointBody],
    rhs: Vec<DVector<Real>>,
) -> Vec<DVector<Real>> {
    let n = rows.len();
    if n < SPARSE_FROM_ROWS {
        let a = dense_matrix(rows, bodies);
        return match a.clone().cholesky() {
            Some(chol) => rhs.iter().map(|b| chol.solve(b)).collect(),
            None => least_squares(a, &rhs),
        };
    }
    KEPT.with(|kept| {
        let mut kept = kept.borrow_mut();
        let hash = key_hash(rows);
        if kept.len() >= SYMBOLIC_KEPT && !kept.contains_key(&hash) {
            kept.clear(); // bounded: the patterns of a new phase of the run are made again
        }
        let bucket = kept.entry(hash).or_default();
        let k = match bucket.iter().position(|s| s.fits(rows)) {
            Some(k) => k,
            None => {
                bucket.push(Symbolic::new(rows, bodies.len()));
                bucket.len() - 1
            }
        };
        let symbolic = &bucket[k];
        if !symbolic.reversed {
            let ordered: Vec<&Row> = rows.iter().collect();
            return sparse_solve(&ordered, bodies, rhs, symbolic);
        }
        // The rows from the last to the first (see [`Symbolic::reversed`]), and the
        // reactions back in the rows' order.
        let ordered: Vec<&Row> = rows.iter().rev().collect();
        let rhs = rhs
            .iter()
            .map(|b| DVector::from_iterator(n, b.iter().rev().copied()))
            .collect();
        sparse_solve(&ordered, bodies, rhs, symbolic)
            .into_iter()
            .map(|x| DVector::from_iterator(n, x.iter().rev().copied()))
            .collect()
    })
}

/// The storage of [`sparse_solve`]'s factor (column-major, n x n for n rows): all zeros
/// between solves. A solve writes only where its factor can be non-zero and puts zeros back
/// there, instead of allocating and clearing the whole square each time.
#[derive(Default)]
struct FactorCells {
    cells: Vec<Real>,
    /// True from a solve's first write until its zeros are back: still true at the next
    /// solve only if one was cut short (a panic), which then clears everything first, so no
    /// result ever depends on what the thread solved before.
    dirty: bool,
}

thread_local! {
    static FACTOR: RefCell<FactorCells> = RefCell::new(FactorCells::default());
}

/// The solve of [`solve_each`] from [`SPARSE_FROM_ROWS`] rows on, the rows in the order
/// `symbolic` was made for.
fn sparse_solve(
    rows: &[&Row],
    bodies: &[JointBody],
    rhs: Vec<DVector<Real>>,
    symbolic: &Symbolic,
) -> Vec<DVector<Real>> {
    let n = rows.len();
    let solved = FACTOR.with(|storage| {
        let storage = &mut *storage.borrow_mut();
        if storage.dirty {
            storage.cells.fill(0.0);
        }
        if storage.cells.len() < n * n {
            storage.cells.resize(n * n, 0.0);
        }
        storage.dirty = true;
        let cells = &mut storage.cells[..n * n];
        lower_matrix(rows, bodies, &symbolic.pairs, cells);
        let solved = factor(cells, n, symbolic).then(|| factor_solve(cells, n, &rhs));
        // Zeros back where the factor was written: its diagonal and its pattern.
        for (j, below) in symbolic.columns.iter().enumerate() {
            cells[j + n * j] = 0.0;
            for &i in below {
                cells[i + n * j] = 0.0;
            }
        }
        storage.dirty = false;
        solved
    });
    solved.unwrap_or_else(|| {
        // (a set of rows that holds a body twice: rare)
        least_squares(matrix(rows, bodies, &symbolic.pairs), &rhs)
    })
}

/// nalgebra's `Cholesky::solve` with the factor L in `cells` (n x n, column-major): L y =
/// b, then L^T x = y, for each right-hand side b. (Over L's non-zeros only, with nalgebra's
/// order of sums, the two took 7 % longer on a pedestrian strike: the dense loops run in
/// SIMD.)
fn factor_solve(cells: &[Real], n: usize, rhs: &[DVector<Real>]) -> Vec<DVector<Real>> {
    let l = DMatrixView::from_slice(cells, n, n);
    rhs.iter()
        .map(|b| {
            let mut x = b.clone();
            l.solve_lower_triangular_unchecked_mut(&mut x);
            l.ad_solve_lower_triangular_unchecked_mut(&mut x);
            x
        })
        .collect()
}

/// Redundant rows: the least-squares reactions for each right-hand side, from one SVD (its
/// solve cannot fail).
fn least_squares(a: DMatrix<Real>, rhs: &[DVector<Real>]) -> Vec<DVector<Real>> {
    let n = a.nrows();
    let svd = a.svd(true, true);
    rhs.iter()
        .map(|b| svd.solve(b, 1e-12).unwrap_or_else(|_| DVector::zeros(n)))
        .collect()
}

/// Entry (i, j) of `J W J^T`: row i's J on the bodies row j moves (`moves`, row j's
/// mobility); zero unless the two rows share a body.
fn entry(ri: &Row, rj: &Row, moves: &([Vector; 2], [Vector; 2])) -> Real {
    let (ma, mb) = moves;
    let mut s = 0.0;
    for (body, m) in [(Some(rj.a), ma), (rj.b, mb)] {
        let Some(body) = body else { continue };
        if ri.a == body {
            s += ri.ja[0].dot(&m[0]) + ri.ja[1].dot(&m[1]);
        }
        if ri.b == Some(body) {
            s += ri.jb[0].dot(&m[0]) + ri.jb[1].dot(&m[1]);
        }
    }
    s
}

/// `J W J^T` for the rows, every pair of rows visited: entry (i, j) is row i's J on the
/// bodies row j moves (zero unless the two rows share a body).
fn dense_matrix(rows: &[Row], bodies: &[JointBody]) -> DMatrix<Real> {
    let n = rows.len();
    let moves: Vec<_> = rows.iter().map(|r| mobility(r, bodies)).collect();
    let mut a = DMatrix::<Real>::zeros(n, n);
    for i in 0..n {
        for j in i..n {
            let s = entry(&rows[i], &rows[j], &moves[j]);
            a[(i, j)] = s;
            a[(j, i)] = s;
        }
    }
    a
}

/// Each body's rows, ascending: `rows_of[first[k]..first[k + 1]]` for body k (a row between
/// a body and itself counted once).
fn rows_of_bodies(rows: &[Row], bodies: usize) -> (Vec<usize>, Vec<usize>) {
    let mut first = vec![0; bodies + 1];
    let other = |r: &Row| r.b.filter(|&b| b != r.a);
    for r in rows {
        first[r.a + 1] += 1;
        if let Some(b) = other(r) {
            first[b + 1] += 1;
        }
    }
    for k in 0..bodies {
        first[k + 1] += first[k];
    }
    let mut fill = first.clone();
    let mut rows_of = vec![0; first[bodies]];
    for (i, r) in rows.iter().enumerate() {
        for body in [Some(r.a), other(r)].into_iter().flatten() {
            rows_of[fill[body]] = i;
            fill[body] += 1;
        }
    }
    (first, rows_of)
}

/// Calls `f(i, j)` once for every pair of rows i <= j that share a body, j ascending.
fn sharing_pairs(rows: &[Row], bodies: usize, mut f: impl FnMut(usize, usize)) {
    let (first, rows_of) = rows_of_bodies(rows, bodies);
    // The last row j each row i was paired with (a row on both of row j's bodies once).
    let mut paired = vec![usize::MAX; rows.len()];
    for (j, rj) in rows.iter().enumerate() {
        for body in [Some(rj.a), rj.b].into_iter().flatten() {
            for &i in &rows_of[first[body]..first[body + 1]] {
                if i > j || paired[i] == j {
                    continue;
                }
                paired[i] = j;
                f(i, j);
            }
        }
    }
}

/// [`dense_matrix`], bit for bit, visiting only the pairs of rows that share a body (`pairs`,
/// [`Symbolic::pairs`] for these rows): a mechanism of many bodies costs what its joints'
/// neighbours do, not the square of its rows.
fn matrix(rows: &[&Row], bodies: &[JointBody], pairs: &[(usize, usize)]) -> DMatrix<Real> {
    let n = rows.len();
    let mut a = DMatrix::<Real>::zeros(n, n);
    lower_matrix(rows, bodies, pairs, a.as_mut_slice());
    for &(i, j) in pairs {
        a[(i, j)] = a[(j, i)];
    }
    a
}

/// The lower triangle (diagonal included) of [`matrix`] written into `cells` (column-major,
/// n x n, zeros where no pair of rows shares a body), the rows in the order factored: what
/// [`factor`] reads.
fn lower_matrix(rows: &[&Row], bodies: &[JointBody], pairs: &[(usize, usize)], cells: &mut [Real]) {
    let n = rows.len();
    let moves: Vec<_> = rows.iter().map(|r| mobility(r, bodies)).collect();
    for &(i, j) in pairs {
        // entry (j, i), j >= i: row j's column i
        cells[j + n * i] = entry(rows[i], rows[j], &moves[j]);
    }
}

/// The pairs of rows (i <= j, j ascending) that share a body ([`sharing_pairs`]).
fn sharing(rows: &[Row], bodies: usize) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    sharing_pairs(rows, bodies, |i, j| pairs.push((i, j)));
    pairs
}

/// Per column j of the matrix of `n` rows, the rows i > j that share a body with row j
/// (ascending), from their sharing pairs: where it can be non-zero below its diagonal.
fn below_diagonal(pairs: &[(usize, usize)], n: usize) -> Vec<Vec<usize>> {
    let mut below = vec![Vec::new(); n];
    for &(i, j) in pairs {
        if i < j {
            below[i].push(j); // j ascends: each list is sorted
        }
    }
    below
}

/// Where L can be non-zero, by column and by row (see [`factor`]), for one pattern of rows.
struct Symbolic {
    /// The bodies of each row it was made for, in the rows' order.
    key: Vec<(usize, Option<usize>)>,
    /// True when the rows are factored from the last to the first: the order whose factor
    /// has fewer entries that can be non-zero. A mechanism's rows come from its root out
    /// (a pedestrian's from the pelvis), and eliminating a body's joint before its children's
    /// fills L in: for a walking pedestrian's 57 rows, 545 entries below the diagonal can be
    /// non-zero in that order, and 317 (the matrix's own: no fill) from the leaves in (the
    /// order reversed), where the factor costs about a third (2.0 against 5.8 us measured on
    /// a 64-row tree).
    reversed: bool,
    /// The pairs of rows (i <= j, in the order factored) that share a body: where the
    /// matrix can be non-zero ([`sharing_pairs`]), kept so that [`matrix`] need not find them.
    pairs: Vec<(usize, usize)>,
    /// Per column, the rows below the diagonal where L may be non-zero ([`structure`]), in
    /// the order factored.
    columns: Vec<Vec<usize>>,
    /// Per row j, the columns k < j where L_jk may be non-zero, ascending.
    in_row: Vec<Vec<usize>>,
}

impl Symbolic {
    fn new(rows: &[Row], bodies: usize) -> Symbolic {
        let n = rows.len();
        let forward_pairs = sharing(rows, bodies);
        let reversed_rows: Vec<Row> = rows.iter().rev().cloned().collect();
        let backward_pairs = sharing(&reversed_rows, bodies);
        let forward = structure(below_diagonal(&forward_pairs, n));
        let backward = structure(below_diagonal(&backward_pairs, n));
        let entries = |columns: &[Vec<usize>]| columns.iter().map(Vec::len).sum::<usize>();
        let reversed = entries(&backward) < entries(&forward);
        let (columns, pairs) = if reversed {
            (backward, backward_pairs)
        } else {
            (forward, forward_pairs)
        };
        let mut in_row = vec![Vec::new(); rows.len()];
        for (k, below) in columns.iter().enumerate() {
            for &i in below {
                in_row[i].push(k);
            }
        }
        Symbolic {
            key: rows.iter().map(|r| (r.a, r.b)).collect(),
            reversed,
            pairs,
            columns,
            in_row,
        }
    }

    /// True when it was made for rows on these bodies.
    fn fits(&self, rows: &[Row]) -> bool {
        self.key.len() == rows.len() && self.key.iter().zip(rows).all(|(k, r)| *k == (r.a, r.b))
    }
}

/// How many patterns' [`Symbolic`]s a thread keeps at most (then it starts again). A
/// pedestrian strike meets about 150 patterns in its first 2 s (joint limits and resting
/// rows coming and going), and keeping the last 8 made one again for 4 % of its 154,000
/// solves.
const SYMBOLIC_KEPT: usize = 512;

thread_local! {
    /// The [`Symbolic`]s made on this thread, by [`key_hash`] of their rows' bodies: a
    /// mechanism solves the same sets of rows (the Runge-Kutta stages', the projections')
    /// many times a step and step after step, so a structure is found again only for rows it
    /// has not met. One depends on the rows' bodies alone, so the results do not depend on
    /// what the thread solved before.
    static KEPT: RefCell<HashMap<u64, Vec<Symbolic>>> = RefCell::new(HashMap::new());
}

/// FNV-1a of the rows' bodies (which body pair each row is on, in order): the key of
/// [`KEPT`], without building the key.
fn key_hash(rows: &[Row]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut add = |v: u64| {
        h ^= v;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    };
    add(rows.len() as u64);
    for r in rows {
        add(r.a as u64);
        add(r.b.map_or(u64::MAX, |b| b as u64));
    }
    h
}

/// Where L can be non-zero below its diagonal, column by column (ascending rows), from where
/// the matrix can be (`below`, [`below_diagonal`]'s): column j's own rows and those of every
/// column whose first row below the diagonal is j (the elimination tree's children), past j.
/// A superset of L's non-zeros whatever the values.
fn structure(below: Vec<Vec<usize>>) -> Vec<Vec<usize>> {
    let mut columns = below;
    for j in 0..columns.len() {
        // Column j is complete here: its children (all before it) are merged in.
        let Some((&parent, rest)) = columns[j].split_first() else {
            continue;
        };
        let merged = merge(&columns[parent], rest);
        columns[parent] = merged;
    }
    columns
}

/// The union of two ascending lists, ascending, each value once.
fn merge(a: &[usize], b: &[usize]) -> Vec<usize> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut k) = (0, 0);
    while i < a.len() || k < b.len() {
        let next = match (a.get(i), b.get(k)) {
            (Some(&x), Some(&y)) => x.min(y),
            (Some(&x), None) => x,
            (None, Some(&y)) => y,
            (None, None) => unreachable!(),
        };
        i += usize::from(a.get(i) == Some(&next));
        k += usize::from(b.get(k) == Some(&next));
        out.push(next);
    }
    out
}

/// Factors the symmetric n x n matrix in `l` (column-major; only its lower triangle, the
/// diagonal included, is read) in place into its lower Cholesky factor L (the strict upper
/// triangle is left as it was); false, as nalgebra's `Cholesky::new` gives None, when a pivot
/// is zero or negative (redundant rows). `symbolic` says where L can be non-zero (made for
/// the matrix's rows).
///
/// The same left-looking algorithm and floating-point operations as nalgebra 0.34's
/// `Cholesky::new`: column j gets `a_ij = -L_jk L_ik + a_ij` for k = 0..j in order, then is
/// divided by the square root of its pivot; but only the columns k whose row j may be
/// non-zero are visited, and in them only the rows that may be, and a zero is neither used
/// nor divided. Adding a zero product leaves an entry as it is (no entry is -0, and every
/// value is finite), so the factor is nalgebra's bit for bit (the tests compare them), while
/// a tree of joints, whose matrix is mostly zeros, costs what its non-zeros do: a walking
/// pedestrian's 57 rows leave 568 of L's 1,653 entries below the diagonal non-zero.
fn factor(l: &mut [Real], n: usize, symbolic: &Symbolic) -> bool {
    let (columns, in_row) = (&symbolic.columns, &symbolic.in_row);
    // Per column k, where row j's entry is in `columns[k]` (j passes each row once).
    let mut at = vec![0usize; n];
    // (column-major: L_ij at l[i + n j])
    for j in 0..n {
        let (done, rest) = l.split_at_mut(j * n);
        let column = &mut rest[..n];
        for &k in &in_row[j] {
            let from = at[k];
            at[k] += 1; // columns[k][from] is j
            let f = -done[j + n * k];
            if f == 0.0 {
                continue;
            }
            let lk = &done[n * k..n * (k + 1)];
            column[j] += f * lk[j];
            for &i in &columns[k][from + 1..] {
                column[i] += f * lk[i];
            }
        }
        let pivot = column[j];
        // nalgebra: None at a zero pivot, and `try_sqrt` None below zero (or NaN).
        if pivot.is_nan() || pivot <= 0.0 {
            return false;
        }
        let d = pivot.sqrt();
        column[j] = d;
        for &i in &columns[j] {
            // (0 / d is 0: only the non-zeros are divided.)
            if column[i] != 0.0 {
                column[i] /= d;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Matrix, Point};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn vector(rng: &mut SmallRng) -> Vector {
        Vector::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        )
    }

    /// A random tree of `n` bodies (body k's parent among 0..k, body 0 on the world), each
    /// joint with 3-6 rows (some with no linear part, as alignments have), then a few rows
    /// between any two bodies (as resting limits add), and, when `redundant`, one row again.
    fn mechanism(rng: &mut SmallRng, n: usize, redundant: bool) -> (Vec<JointBody>, Vec<Row>) {
        let bodies: Vec<_> = (0..n)
            .map(|_| {
                let m = Matrix::from_diagonal(&Vector::new(
                    rng.random_range(0.05..20.0),
                    rng.random_range(0.05..20.0),
                    rng.random_range(0.05..20.0),
                ));
                let r = nalgebra::Rotation3::new(vector(rng)).into_inner();
                JointBody {
                    x: Point::origin(),
                    r,
                    v: Vector::zeros(),
                    w: Vector::zeros(),
                    inv_mass: 1.0 / rng.random_range(0.5..80.0),
                    inv_inertia: r * m * r.transpose(),
                }
            })
            .collect();
        let mut rows = Vec::new();
        let row = |rng: &mut SmallRng, a: usize, b: Option<usize>| {
            let linear = rng.random_bool(0.6);
            let part = |rng: &mut SmallRng| if linear { vector(rng) } else { Vector::zeros() };
            Row {
                a,
                b,
                ja: [part(rng), vector(rng)],
                jb: [part(rng), vector(rng)],
                c: 0.0,
                bias: 0.0,
            }
        };
        for k in 0..n {
            let (a, b) = if k == 0 {
                (0, None)
            } else {
                (rng.random_range(0..k), Some(k))
            };
            for _ in 0..rng.random_range(3..=6) {
                rows.push(row(rng, a, b));
            }
        }
        for _ in 0..rng.random_range(0..4) {
            let (a, b) = (rng.random_range(0..n), rng.random_range(0..n));
            rows.push(row(rng, a, (a != b).then_some(b)));
        }
        if redundant {
            let k = rng.random_range(0..rows.len());
            rows.push(rows[k].clone());
        }
        (bodies, rows)
    }

    fn bits<'a>(m: impl IntoIterator<Item = &'a Real>) -> Vec<u64> {
        m.into_iter().map(|x| x.to_bits()).collect()
    }

    /// Where the matrix of the rows can be non-zero below its diagonal ([`below_diagonal`]).
    fn pattern(rows: &[Row], bodies: usize) -> Vec<Vec<usize>> {
        below_diagonal(&sharing(rows, bodies), rows.len())
    }

    /// The rows in the order a [`Symbolic`] factors them.
    fn in_order(rows: &[Row], symbolic: &Symbolic) -> Vec<Row> {
        if symbolic.reversed {
            rows.iter().rev().cloned().collect()
        } else {
            rows.to_vec()
        }
    }

    /// nalgebra's dense Cholesky solve of the rows in the order the solve takes them (their
    /// own below [`SPARSE_FROM_ROWS`], the [`Symbolic`]'s from there), the reactions back in
    /// the rows' order; None where it finds the matrix not positive definite.
    fn dense_solve(rows: &[Row], bodies: &[JointBody], rhs: &DVector<Real>) -> Option<Vec<u64>> {
        let n = rows.len();
        let reversed = n >= SPARSE_FROM_ROWS && Symbolic::new(rows, bodies.len()).reversed;
        if !reversed {
            return dense_matrix(rows, bodies)
                .cholesky()
                .map(|c| bits(&c.solve(rhs)));
        }
        let back: Vec<Row> = rows.iter().rev().cloned().collect();
        let rhs = DVector::from_iterator(n, rhs.iter().rev().copied());
        let x = dense_matrix(&back, bodies).cholesky()?.solve(&rhs);
        Some(bits(x.iter().rev()))
    }

    /// The matrix, its factor and the solution are the dense ones (nalgebra's Cholesky, the
    /// rows in the order factored) bit for bit, over random trees of 1-20 bodies (5-100 rows,
    /// either side of [`SPARSE_FROM_ROWS`]); and the factor fails exactly where nalgebra's
    /// does.
    #[test]
    fn the_sparse_solve_is_the_dense_one_bit_for_bit() {
        let mut rng = SmallRng::seed_from_u64(20261127);
        let (mut factored, mut reversed) = (0, 0);
        for case in 0..400 {
            let n = rng.random_range(1..=20);
            let (bodies, rows) = mechanism(&mut rng, n, case % 5 == 4);
            let symbolic = Symbolic::new(&rows, bodies.len());
            reversed += usize::from(symbolic.reversed && rows.len() >= SPARSE_FROM_ROWS);
            let ordered = in_order(&rows, &symbolic);
            let refs: Vec<&Row> = ordered.iter().collect();
            let a = matrix(&refs, &bodies, &symbolic.pairs);
            assert_eq!(
                bits(&a),
                bits(&dense_matrix(&ordered, &bodies)),
                "case {case}"
            );
            let mut l = a.clone();
            let ours = factor(l.as_mut_slice(), rows.len(), &symbolic);
            let theirs = a.clone().cholesky();
            assert_eq!(ours, theirs.is_some(), "case {case}");
            let rhs = DVector::from_fn(rows.len(), |_, _| rng.random_range(-1e3..1e3));
            if let Some(chol) = theirs {
                factored += 1;
                assert_eq!(bits(&l.lower_triangle()), bits(&chol.l()), "case {case}");
            }
            if let Some(expected) = dense_solve(&rows, &bodies, &rhs) {
                assert_eq!(
                    bits(&solve(&rows, &bodies, rhs.clone())),
                    expected,
                    "case {case}"
                );
            }
            // Other values on the same bodies: the structure found for the rows before is
            // used again (the solve's cache), with the same bits as nalgebra's.
            let other: Vec<Row> = rows
                .iter()
                .map(|r| Row {
                    ja: [r.ja[0] * 1.5, r.ja[1] * 0.7],
                    jb: [r.jb[0] * 0.9, r.jb[1] * 1.3],
                    ..r.clone()
                })
                .collect();
            if let Some(expected) = dense_solve(&other, &bodies, &rhs) {
                let x = solve(&other, &bodies, rhs.clone());
                assert_eq!(bits(&x), expected, "case {case}, again");
            }
        }
        // The factor's storage is all zeros again after every solve (and so after these,
        // of many sizes, some failing).
        FACTOR.with(|f| {
            let f = f.borrow();
            assert!(!f.dirty && f.cells.iter().all(|&x| x.to_bits() == 0));
        });
        assert!(
            factored > 250,
            "only {factored} cases were positive definite"
        );
        assert!(
            reversed > 20,
            "only {reversed} cases were factored reversed"
        );
    }

    /// A solve cut short (a panic between the factor's first write and its zeros put back)
    /// leaves its thread's storage dirty: the next solve clears it and gives nalgebra's bits.
    #[test]
    fn a_solve_cut_short_leaves_no_trace() {
        let mut rng = SmallRng::seed_from_u64(11);
        let (bodies, rows) = loop {
            let (bodies, rows) = mechanism(&mut rng, 12, false);
            if rows.len() >= SPARSE_FROM_ROWS {
                break (bodies, rows);
            }
        };
        let rhs = DVector::from_fn(rows.len(), |_, _| rng.random_range(-1e3..1e3));
        let expected = dense_solve(&rows, &bodies, &rhs).expect("positive definite");
        FACTOR.with(|f| {
            let mut f = f.borrow_mut();
            f.cells = vec![1.5; rows.len() * rows.len() + 7];
            f.dirty = true;
        });
        assert_eq!(bits(&solve(&rows, &bodies, rhs)), expected);
        FACTOR.with(|f| assert!(!f.borrow().dirty));
    }

    /// A tree whose joints are listed from its root out (as a pedestrian's are, from the
    /// pelvis): factored from the leaves in, where L has no entry the matrix has not.
    #[test]
    fn a_tree_listed_from_its_root_is_factored_from_its_leaves_without_fill() {
        let mut rng = SmallRng::seed_from_u64(7);
        let (bodies, _) = mechanism(&mut rng, 16, false);
        // body 0 on the world and three limbs of five bodies on it (1-5, 6-10, 11-15), each
        // body on the one before it, the first of each on body 0; root first, 4 rows a joint
        let mut rows = Vec::new();
        for k in 0..bodies.len() {
            let (a, b) = match k {
                0 => (0, None),
                1 | 6 | 11 => (0, Some(k)),
                _ => (k - 1, Some(k)),
            };
            for _ in 0..4 {
                let (ja, jb) = (
                    [vector(&mut rng), vector(&mut rng)],
                    [vector(&mut rng), vector(&mut rng)],
                );
                rows.push(Row {
                    a,
                    b,
                    ja,
                    jb,
                    c: 0.0,
                    bias: 0.0,
                });
            }
        }
        assert!(rows.len() >= SPARSE_FROM_ROWS);
        let symbolic = Symbolic::new(&rows, bodies.len());
        assert!(symbolic.reversed);
        let below = pattern(&in_order(&rows, &symbolic), bodies.len());
        assert_eq!(symbolic.columns, below, "no fill");
        let forward = structure(pattern(&rows, bodies.len()));
        let entries = |c: &[Vec<usize>]| c.iter().map(Vec::len).sum::<usize>();
        assert!(entries(&forward) > entries(&below));
    }
}
