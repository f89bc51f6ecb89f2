//! Smoothing of street networks drawn on a mesh, which are stair-shaped where they run
//! diagonally to the quads.
//!
//! * [`decompose`] splits a network into *snakes*: maximal chains of edges between vertices of
//!   valence ≠ 2 (junctions and dead ends) and level changes (paper, appendix "Snake-based
//!   smoothing").
//! * [`smooth`] is the paper's smoother: active contours [Kass et al. 1988] with tension,
//!   stiffness and inertia energies (eq. 21), minimised by gradient descent with adaptive steps
//!   (eq. 22); stiffer major roads, more inert local streets; streets leave junctions along the
//!   mesh's own edge direction (90° on quad meshes).
//! * [`fair`] is the fairing of Yang et al. 2013, §6: fairness (eq. 6) plus closeness (eq. 7),
//!   a quadratic energy minimised exactly by one banded linear solve per iteration.
//!
//! **Scale.** Both smoothers work per snake in normalised coordinates `q = (p − p₀) / L`, with
//! `p₀` the snake's first point and `L` the mean (deduplicated) edge length of the whole
//! network, so energies are invariant to translation and uniform scaling. Each edge is
//! subdivided into `s` pieces; the discrete terms are weighted `α·s`, `β·s³` and `γ/s`, the
//! Riemann sums of `∫|q′|²`, `∫|q″|²` and `∫|q − q⁰|²` over a parameter in which every
//! original edge has length 1. So the weights mean the same for any `s` and mesh spacing, and
//! for `s = 1` the energy is exactly eq. 21 divided by `L²`. The smoothing length of
//! stiffness against inertia is `(β/γ)^¼` original edges.
//!
//! End points of snakes never move; they are copied bit for bit into the output.
use crate::design::streets::{chains, Topology};
pub use crate::design::streets::{decompose, Snake, StreetEdge, StreetGraph};
use crate::geometry::{dot, sub, P};
use serde::{Deserialize, Serialize};

/// Smoothed snakes plus a summary of the optimisation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SmoothResult {
    /// The snakes, in [`decompose`] order.
    pub snakes: Vec<Snake>,
    /// Total (normalised) energy of the subdivided, unsmoothed snakes.
    pub energy_before: f64,
    /// Total (normalised) energy after smoothing.
    pub energy_after: f64,
    /// Most iterations any snake took (gradient steps for [`smooth`], solves for [`fair`]).
    pub iterations: usize,
    /// Every snake met its stopping criterion before the iteration limit.
    pub converged: bool,
}

/// Weights of the three snake energies (paper eq. 21): α, β, γ.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SnakeWeights {
    /// α: membrane term `|p_{i+1} − p_i|²`; pulls the street shorter.
    pub tension: f64,
    /// β: thin-plate term `|p_{i−1} − 2p_i + p_{i+1}|²`; rounds corners.
    pub stiffness: f64,
    /// γ: `|p_i − p_i⁰|²`; keeps the street near its mesh position.
    pub inertia: f64,
}

impl Default for SnakeWeights {
    /// The collector-road weights (α 0.5, β 4, γ 1).
    fn default() -> Self {
        SnakeWeights { tension: 0.5, stiffness: 4.0, inertia: 1.0 }
    }
}

/// Settings of [`smooth`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SnakeOptions {
    /// Pieces each edge is subdivided into (at least 1).
    pub subdivisions: usize,
    /// Weights per level. A level not listed takes the nearest listed one (the lower on ties);
    /// an empty list means [`SnakeWeights::default`].
    pub weights: Vec<(u8, SnakeWeights)>,
    /// Stop when the last 10 steps lowered a snake's energy by less than 10× this fraction.
    pub tolerance: f64,
    /// Most gradient steps per snake.
    pub max_iterations: usize,
    /// Keep the first point next to a junction (valence ≥ 3) on the line of the original edge,
    /// so streets leave junctions in the mesh's direction (90° on quad meshes).
    pub junction_tangents: bool,
    /// Nesterov momentum with adaptive restart instead of the paper's plain descent, whose
    /// step doubles on success. Plain descent needs about `16·(β/γ)·s⁴` steps (65 536 for
    /// level 1 at s = 4) to converge; with momentum about the square root of that.
    pub momentum: bool,
}

impl Default for SnakeOptions {
    /// Four subdivisions; tolerance 1e-8; 20 000 steps; junction tangents and momentum on.
    /// Weights follow the paper: major and collector roads stiffer, local streets and
    /// cul-de-sacs more inert, with smoothing lengths `(β/γ)^¼` of 2, 1.4, 0.84 and 0.59 edges:
    /// level 1 (α 0.5, β 16, γ 1), 2 (0.5, 4, 1), 3 (0.25, 1, 2), 4 (0.25, 0.5, 4).
    fn default() -> Self {
        let w = |tension, stiffness, inertia| SnakeWeights { tension, stiffness, inertia };
        SnakeOptions {
            subdivisions: 4,
            weights: vec![
                (1, w(0.5, 16.0, 1.0)),
                (2, w(0.5, 4.0, 1.0)),
                (3, w(0.25, 1.0, 2.0)),
                (4, w(0.25, 0.5, 4.0)),
            ],
            tolerance: 1e-8,
            max_iterations: 20_000,
            junction_tangents: true,
            momentum: true,
        }
    }
}

impl SnakeOptions {
    /// The weights used for `level`.
    pub fn weights_for(&self, level: u8) -> SnakeWeights {
        self.weights
            .iter()
            .min_by_key(|(l, _)| ((*l as i32 - level as i32).abs(), *l))
            .map_or_else(SnakeWeights::default, |&(_, w)| w)
    }
}

/// Settings of [`fair`] (Yang et al. 2013, §6).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FairOptions {
    /// Pieces each edge is subdivided into (at least 1).
    pub subdivisions: usize,
    /// Weight of the fairness term (eq. 6), scaled like the snakes' stiffness.
    pub fairness: f64,
    /// Weight of the closeness term (eq. 7), scaled like the snakes' inertia.
    pub closeness: f64,
    /// Most iterations (Yang et al. use 10).
    pub iterations: usize,
    /// As [`SnakeOptions::junction_tangents`].
    pub junction_tangents: bool,
}

impl Default for FairOptions {
    /// Four subdivisions, fairness 4, closeness 1 (smoothing length 1.4 edges), 10 iterations,
    /// junction tangents on.
    fn default() -> Self {
        FairOptions { subdivisions: 4, fairness: 4.0, closeness: 1.0, iterations: 10, junction_tangents: true }
    }
}

/// One squared term `c·|Σ a_k q[idx_k] − anchor|²` of a snake energy.
struct Term {
    c: f64,
    idx: [usize; 3],
    a: [f64; 3],
    len: usize,
    /// Subtract `q⁰[idx[0]]` (inertia / closeness).
    anchored: bool,
}

/// The terms of eq. 21 on `m` distinct points (cyclic when `closed` and `m ≥ 3`).
fn terms(m: usize, closed: bool, w: &SnakeWeights) -> Vec<Term> {
    let cyc = closed && m >= 3;
    let at = |i: usize| i % m;
    let mut out = Vec::new();
    let mut push = |c: f64, idx: [usize; 3], a: [f64; 3], len, anchored| {
        if c != 0.0 {
            out.push(Term { c, idx, a, len, anchored });
        }
    };
    let segs = if cyc { m } else { m.saturating_sub(1) };
    for i in 0..segs {
        push(w.tension, [i, at(i + 1), 0], [-1.0, 1.0, 0.0], 2, false);
    }
    let (lo, hi) = if cyc { (0, m) } else { (1, m.saturating_sub(1)) };
    for i in lo..hi {
        push(w.stiffness, [at(i + m - 1), i, at(i + 1)], [1.0, -2.0, 1.0], 3, false);
    }
    for i in 0..m {
        push(w.inertia, [i, 0, 0], [1.0, 0.0, 0.0], 1, true);
    }
    out
}

fn residual(t: &Term, q: &[P], q0: &[P]) -> P {
    let mut r = if t.anchored { [-q0[t.idx[0]][0], -q0[t.idx[0]][1]] } else { [0.0; 2] };
    for k in 0..t.len {
        r[0] += t.a[k] * q[t.idx[k]][0];
        r[1] += t.a[k] * q[t.idx[k]][1];
    }
    r
}

fn total(ts: &[Term], q: &[P], q0: &[P]) -> f64 {
    ts.iter().map(|t| t.c * dot(residual(t, q, q0), residual(t, q, q0))).sum()
}

fn gradient(ts: &[Term], q: &[P], q0: &[P], g: &mut [P]) {
    g.iter_mut().for_each(|x| *x = [0.0; 2]);
    for t in ts {
        let r = residual(t, q, q0);
        for k in 0..t.len {
            let f = 2.0 * t.c * t.a[k];
            g[t.idx[k]][0] += f * r[0];
            g[t.idx[k]][1] += f * r[1];
        }
    }
}

/// The paper's snake energy (eq. 21) of one polyline against its original positions:
/// `Σ α|p_{i+1} − p_i|² + β|p_{i−1} − 2p_i + p_{i+1}|² + γ|p_i − p_i⁰|²`, in the units given.
/// For `closed`, both slices repeat the first point at the end (as [`Snake::points`]) and the
/// differences wrap around. [`smooth`] applies it to normalised coordinates with scaled weights
/// (see the module docs). Extra points of the longer slice are ignored.
pub fn energy(points: &[[f64; 2]], original: &[[f64; 2]], weights: &SnakeWeights, closed: bool) -> f64 {
    let n = points.len().min(original.len());
    let m = if closed && n > 1 { n - 1 } else { n };
    total(&terms(m, closed, weights), &points[..m], &original[..m])
}

/// How a subdivided point may move.
#[derive(Clone, Copy, PartialEq)]
enum Dof {
    Fixed,
    Free,
    /// On the line through `c` with unit direction `u`.
    Line {
        c: P,
        u: P,
    },
}

fn project(c: P, u: P, p: P) -> P {
    let t = dot(sub(p, c), u);
    [c[0] + t * u[0], c[1] + t * u[1]]
}

/// One subdivided snake in normalised coordinates (distinct points only when closed).
struct Work {
    closed: bool,
    origin: P,
    scale: f64,
    raw: Vec<P>,
    q0: Vec<P>,
    q: Vec<P>,
    dofs: Vec<Dof>,
}

impl Work {
    fn new(g: &StreetGraph, t: &Topology, s: &Snake, subdivisions: usize, tangents: bool, scale: f64) -> Self {
        let pieces = subdivisions.max(1);
        let mut raw = Vec::new();
        for w in s.vertices.windows(2) {
            let (a, b) = (g.positions[w[0] as usize], g.positions[w[1] as usize]);
            for j in 0..pieces {
                let f = j as f64 / pieces as f64;
                raw.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
            }
        }
        raw.push(g.positions[*s.vertices.last().unwrap() as usize]);
        let origin = raw[0];
        let n = raw.len() - usize::from(s.closed);
        let q0: Vec<P> = raw[..n].iter().map(|&p| [(p[0] - origin[0]) / scale, (p[1] - origin[1]) / scale]).collect();
        let mut dofs = vec![Dof::Free; n];
        dofs[0] = Dof::Fixed;
        if !s.closed {
            dofs[n - 1] = Dof::Fixed;
            let ends = [(0, 1, s.vertices[0]), (n - 1, n - 2, s.vertices[s.vertices.len() - 1])];
            for (end, next, v) in ends {
                let d = sub(q0[next], q0[end]);
                let len = dot(d, d).sqrt();
                if !tangents || t.adj[v as usize].len() < 3 || dofs[next] == Dof::Fixed || len == 0.0 {
                    continue;
                }
                dofs[next] = match dofs[next] {
                    Dof::Free => Dof::Line { c: q0[end], u: [d[0] / len, d[1] / len] },
                    _ => Dof::Fixed,
                };
            }
        }
        Work { closed: s.closed, origin, scale, raw, q: q0.clone(), q0, dofs }
    }

    /// The output polyline in original units; fixed points are copied exactly.
    fn points(&self) -> Vec<P> {
        let mut out: Vec<P> = (self.q.iter().zip(&self.dofs).zip(&self.raw))
            .map(|((q, d), r)| match d {
                Dof::Fixed => *r,
                _ => [self.origin[0] + self.scale * q[0], self.origin[1] + self.scale * q[1]],
            })
            .collect();
        if out.len() < self.raw.len() {
            out.push(out[0]);
        }
        out
    }

    /// Zeroes fixed components of a gradient and projects line-constrained ones onto the line.
    fn constrain_gradient(&self, g: &mut [P]) {
        for (gi, d) in g.iter_mut().zip(&self.dofs) {
            match *d {
                Dof::Fixed => *gi = [0.0; 2],
                Dof::Line { u, .. } => *gi = project([0.0; 2], u, *gi),
                Dof::Free => {}
            }
        }
    }
}

/// Weights scaled for `s` subdivisions (see the module docs).
fn scaled(w: SnakeWeights, s: usize) -> SnakeWeights {
    let s = s.max(1) as f64;
    SnakeWeights { tension: w.tension * s, stiffness: w.stiffness * s.powi(3), inertia: w.inertia / s }
}

/// Gradient descent with adaptive step on one snake (paper eq. 22). The first step is `1/λ`
/// for a Gershgorin bound `λ` of the Hessian, safe for plain descent. A step that does not
/// raise the energy is taken; otherwise the step is halved and retried. Plain descent
/// (`momentum` off) doubles the step after each success. With `momentum` the step is taken
/// from the Nesterov point `x + k/(k+3)·(x − x_prev)` and not grown; a rise first restarts the
/// momentum (k = 0; O'Donoghue & Candès 2015) before halving. Stops when the last 10 steps
/// together lowered the energy by less than `10·tol` relatively. Returns (steps, converged).
fn descend(w: &mut Work, ts: &[Term], tol: f64, max_iterations: usize, momentum: bool) -> (usize, bool) {
    const WINDOW: usize = 10;
    let mut row = vec![0.0f64; w.q.len()];
    for t in ts {
        let abs: f64 = t.a[..t.len].iter().map(|a| a.abs()).sum();
        for k in 0..t.len {
            row[t.idx[k]] += 2.0 * t.c * t.a[k].abs() * abs;
        }
    }
    let lambda = row.iter().cloned().fold(0.0, f64::max);
    if lambda == 0.0 {
        return (0, true);
    }
    let (mut step, mut k) = (1.0 / lambda, 0usize);
    let mut e = total(ts, &w.q, &w.q0);
    let mut history = vec![e];
    let (mut g, mut y, mut trial, mut prev) = (vec![[0.0; 2]; w.q.len()], w.q.clone(), w.q.clone(), w.q.clone());
    for it in 0..max_iterations {
        let e_new = loop {
            let beta = if momentum { k as f64 / (k as f64 + 3.0) } else { 0.0 };
            for (i, d) in w.dofs.iter().enumerate() {
                let p = [w.q[i][0] + beta * (w.q[i][0] - prev[i][0]), w.q[i][1] + beta * (w.q[i][1] - prev[i][1])];
                y[i] = if let Dof::Line { c, u } = *d { project(c, u, p) } else { p };
            }
            gradient(ts, &y, &w.q0, &mut g);
            w.constrain_gradient(&mut g);
            if beta == 0.0 && g.iter().all(|x| *x == [0.0; 2]) {
                return (it, true);
            }
            for (i, d) in w.dofs.iter().enumerate() {
                let p = [y[i][0] - step * g[i][0], y[i][1] - step * g[i][1]];
                trial[i] = if let Dof::Line { c, u } = *d { project(c, u, p) } else { p };
            }
            let e_t = total(ts, &trial, &w.q0);
            if e_t <= e {
                break e_t;
            }
            if beta > 0.0 {
                k = 0;
                continue;
            }
            step *= 0.5;
            if step * lambda < 1e-12 {
                return (it, true); // no descent left at machine precision
            }
        };
        std::mem::swap(&mut prev, &mut w.q);
        std::mem::swap(&mut w.q, &mut trial);
        k += 1;
        if !momentum {
            step *= 2.0;
        }
        e = e_new;
        history.push(e);
        if history.len() > WINDOW
            && history[history.len() - 1 - WINDOW] - e < WINDOW as f64 * tol * e.max(f64::MIN_POSITIVE)
        {
            return (it + 1, true);
        }
    }
    (max_iterations, false)
}

/// The paper's snake smoothing (appendix, eqs. 21–22): [`decompose`], subdivide every edge
/// into `opts.subdivisions` pieces, and minimise each snake's energy by gradient descent with
/// adaptive steps, using the weights of the snake's level. Snake ends stay fixed; with
/// `opts.junction_tangents` the point next to a junction slides only along the original edge.
pub fn smooth(g: &StreetGraph, opts: &SnakeOptions) -> SmoothResult {
    run(g, opts.subdivisions, opts.junction_tangents, |s, w| {
        let ts = terms(w.q.len(), s.closed, &scaled(opts.weights_for(s.level), opts.subdivisions));
        let before = total(&ts, &w.q, &w.q0);
        let (it, ok) = descend(w, &ts, opts.tolerance, opts.max_iterations, opts.momentum);
        (before, total(&ts, &w.q, &w.q0), it, ok)
    })
}

/// Yang et al. 2013, §6 fairing: per snake, minimise `w_fair·Σ|p_{i−1} − 2p_i + p_{i+1}|²`
/// (eq. 6) `+ w_close·Σ|p_i − p_i⁰|²` (eq. 7), closeness always to the ORIGINAL positions,
/// snake ends fixed, same subdivision and scaling as [`smooth`]. The energy is quadratic, so
/// the free points are found exactly by one banded Cholesky solve (pentadiagonal for open
/// snakes; a closed one's points are ordered 1, m−1, 2, m−2, … to keep the cycle in a band of
/// width 4). Points next to junctions (with `junction_tangents`) slide on their edge line,
/// as Yang's intersections slide on the boundary, and this is what the iterations are for:
/// each first moves those points to their exact optimum on the line with the rest held, then
/// solves for the rest. This block coordinate descent never raises the energy; it runs
/// `opts.iterations` times or until an iteration changes the energy by less than 1e-12
/// relatively (`converged`). Without sliding points the first solve is exact and final.
pub fn fair(g: &StreetGraph, opts: &FairOptions) -> SmoothResult {
    let w = SnakeWeights { tension: 0.0, stiffness: opts.fairness, inertia: opts.closeness };
    run(g, opts.subdivisions, opts.junction_tangents, |s, work| {
        let ts = terms(work.q.len(), s.closed, &scaled(w, opts.subdivisions));
        let before = total(&ts, &work.q, &work.q0);
        let sliding = work.dofs.iter().any(|d| matches!(d, Dof::Line { .. }));
        let (mut e, mut it, mut ok) = (before, 0, false);
        while it < opts.iterations && !ok {
            it += 1;
            slide(work, &ts);
            solve_free(work, &ts);
            let e_new = total(&ts, &work.q, &work.q0);
            ok = !sliding || (e - e_new).abs() <= 1e-12 * e.max(f64::MIN_POSITIVE);
            e = e_new;
        }
        (before, e, it, ok)
    })
}

/// The smoothing a city spec asks for (`[smoothing] method`), with default settings: [`smooth`],
/// [`fair`], or for `none` the unsmoothed snakes of [`decompose`].
pub fn by_method(g: &StreetGraph, method: super::spec::SmoothingMethod) -> SmoothResult {
    use super::spec::SmoothingMethod;
    match method {
        SmoothingMethod::Snake => smooth(g, &SnakeOptions::default()),
        SmoothingMethod::Fair => fair(g, &FairOptions::default()),
        SmoothingMethod::None => {
            SmoothResult { snakes: decompose(g), energy_before: 0.0, energy_after: 0.0, iterations: 0, converged: true }
        }
    }
}

/// Decompose, subdivide, optimise each snake with `f` → (before, after, iterations, converged).
fn run(
    g: &StreetGraph,
    subdivisions: usize,
    tangents: bool,
    mut f: impl FnMut(&Snake, &mut Work) -> (f64, f64, usize, bool),
) -> SmoothResult {
    let t = Topology::new(g);
    let scale = t.length_scale(g);
    let mut res =
        SmoothResult { snakes: Vec::new(), energy_before: 0.0, energy_after: 0.0, iterations: 0, converged: true };
    for mut s in chains(g, &t) {
        let mut w = Work::new(g, &t, &s, subdivisions, tangents, scale);
        let (before, after, it, ok) = f(&s, &mut w);
        res.energy_before += before;
        res.energy_after += after;
        res.iterations = res.iterations.max(it);
        res.converged &= ok;
        s.points = w.points();
        res.snakes.push(s);
    }
    res
}

/// Moves every line-constrained point to the energy minimum on its line, others held.
fn slide(w: &mut Work, ts: &[Term]) {
    let mut g = vec![[0.0; 2]; w.q.len()];
    for i in 0..w.q.len() {
        let Dof::Line { c, u } = w.dofs[i] else { continue };
        w.q[i] = c;
        gradient(ts, &w.q, &w.q0, &mut g);
        // The Hessian block of point i is 2·Σ c·a_i² times the identity.
        let h: f64 = ts
            .iter()
            .flat_map(|t| (0..t.len).filter(move |&k| t.idx[k] == i).map(move |k| 2.0 * t.c * t.a[k] * t.a[k]))
            .sum();
        if h > 0.0 {
            let s = -dot(g[i], u) / h;
            w.q[i] = [c[0] + s * u[0], c[1] + s * u[1]];
        }
    }
}

/// Moves the free points to the exact minimum with the rest held: the energy is quadratic, so
/// one Newton step `H_ff·Δ = −∇_f E` (`H = 2·Σ c·a·aᵀ`, SPD band) lands on it. Leaves the points
/// unchanged if `H_ff` is not positive definite (e.g. all weights zero).
fn solve_free(w: &mut Work, ts: &[Term]) {
    let m = w.q.len();
    let mut order: Vec<usize> = (0..m).collect();
    if w.closed {
        // 0 is fixed; interleave its two sides, 1, m−1, 2, m−2, …, to keep the wrap in the band.
        order = (1..m).map(|k| if k % 2 == 1 { 1 + k / 2 } else { m - k / 2 }).collect();
    }
    order.retain(|&i| w.dofs[i] == Dof::Free);
    let (n, mut pos) = (order.len(), vec![usize::MAX; m]);
    for (k, &i) in order.iter().enumerate() {
        pos[i] = k;
    }
    // Stencils span 3 consecutive points: band width 2 in path order, 4 interleaved.
    let bw = if w.closed { 4 } else { 2 };
    let mut band = vec![0.0; n * (bw + 1)];
    for t in ts {
        for j in (0..t.len).filter(|&j| pos[t.idx[j]] != usize::MAX) {
            for k in (0..t.len).filter(|&k| pos[t.idx[k]] <= pos[t.idx[j]]) {
                let (pj, pk) = (pos[t.idx[j]], pos[t.idx[k]]);
                debug_assert!(pj - pk <= bw);
                band[pj * (bw + 1) + (pj - pk)] += 2.0 * t.c * t.a[j] * t.a[k];
            }
        }
    }
    let mut g = vec![[0.0; 2]; m];
    gradient(ts, &w.q, &w.q0, &mut g);
    let mut x: Vec<P> = order.iter().map(|&i| [-g[i][0], -g[i][1]]).collect();
    if cholesky_solve(&mut band, n, bw, &mut x) {
        for (k, &i) in order.iter().enumerate() {
            w.q[i] = [w.q[i][0] + x[k][0], w.q[i][1] + x[k][1]];
        }
    }
}

/// Solves `A·x = b` in place (two right-hand sides) for a symmetric band matrix stored by rows
/// of its lower band, `a[i·(w+1) + d] = A[i][i−d]`, by banded Cholesky `A = L·Lᵀ` (`a` is
/// overwritten by `L`). False if `A` is not positive definite.
fn cholesky_solve(a: &mut [f64], n: usize, w: usize, x: &mut [P]) -> bool {
    let at = |i: usize, j: usize| i * (w + 1) + (i - j);
    for i in 0..n {
        for j in i.saturating_sub(w)..=i {
            let s = a[at(i, j)] - (i.saturating_sub(w)..j).map(|k| a[at(i, k)] * a[at(j, k)]).sum::<f64>();
            if i > j {
                a[at(i, j)] = s / a[at(j, j)];
            } else if s > 0.0 {
                a[at(i, i)] = s.sqrt();
            } else {
                return false;
            }
        }
    }
    for i in 0..n {
        let s =
            (i.saturating_sub(w)..i).fold(x[i], |s, k| [s[0] - a[at(i, k)] * x[k][0], s[1] - a[at(i, k)] * x[k][1]]);
        x[i] = [s[0] / a[at(i, i)], s[1] / a[at(i, i)]];
    }
    for i in (0..n).rev() {
        let s =
            (i + 1..n.min(i + w + 1)).fold(x[i], |s, k| [s[0] - a[at(k, i)] * x[k][0], s[1] - a[at(k, i)] * x[k][1]]);
        x[i] = [s[0] / a[at(i, i)], s[1] / a[at(i, i)]];
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::dist;

    fn edge(a: u32, b: u32, level: u8) -> StreetEdge {
        StreetEdge { a, b, level }
    }

    /// A path of `steps` unit stair steps from the origin.
    fn staircase(steps: usize, level: u8) -> StreetGraph {
        let mut positions = vec![[0.0, 0.0]];
        for i in 0..2 * steps {
            let [x, y] = positions[i];
            positions.push(if i % 2 == 0 { [x + 1.0, y] } else { [x, y + 1.0] });
        }
        StreetGraph { positions, edges: (0..2 * steps as u32).map(|i| edge(i, i + 1, level)).collect() }
    }

    /// An isolated cycle of 8 edges, partly stair-shaped.
    fn ring() -> StreetGraph {
        let mut g = staircase(2, 3);
        g.positions.extend([[1.0, 3.0], [0.0, 2.0], [-1.0, 1.0]]);
        g.edges.extend([edge(4, 5, 3), edge(5, 6, 3), edge(6, 7, 3), edge(7, 0, 3)]);
        g
    }

    /// A junction at vertex 0 = the origin with `arms` staircase arms, rotated by 90° each.
    fn star(arms: usize) -> StreetGraph {
        let mut g = StreetGraph { positions: vec![[0.0, 0.0]], edges: vec![] };
        for k in 0..arms {
            let (c, s) = ([1.0, 0.0, -1.0, 0.0][k], [0.0, 1.0, 0.0, -1.0][k]);
            for (i, &[x, y]) in staircase(3, 2).positions.iter().enumerate().skip(1) {
                let v = g.positions.len() as u32;
                g.edges.push(edge(if i == 1 { 0 } else { v - 1 }, v, 2));
                g.positions.push([c * x - s * y, s * x + c * y]);
            }
        }
        g
    }

    fn edge_set(snakes: &[Snake]) -> Vec<(u32, u32)> {
        let mut out: Vec<_> =
            snakes.iter().flat_map(|s| s.vertices.windows(2).map(|w| (w[0].min(w[1]), w[0].max(w[1])))).collect();
        out.sort();
        out
    }

    fn cross(o: P, a: P, b: P) -> f64 {
        let (u, v) = (sub(a, o), sub(b, o));
        u[0] * v[1] - u[1] * v[0]
    }

    /// Ends of every snake are bitwise the graph positions.
    fn assert_ends_fixed(g: &StreetGraph, r: &SmoothResult) {
        for s in &r.snakes {
            assert_eq!(s.points[0], g.positions[s.vertices[0] as usize]);
            assert_eq!(s.points.last(), s.vertices.last().map(|&v| &g.positions[v as usize]));
        }
    }

    #[test]
    fn decompose_covers_every_edge_once() {
        let mut g = star(4);
        let n = g.positions.len() as u32;
        // A square cycle (ids out of order), a path changing level, a loop hanging off a junction.
        g.positions.extend([[10.0, 0.0], [11.0, 0.0], [11.0, 1.0], [10.0, 1.0], [20.0, 0.0], [21.0, 0.0], [22.0, 0.0]]);
        g.positions.extend([[30.0, 0.0], [31.0, 0.0], [31.0, 1.0], [29.0, 0.0]]);
        g.edges.extend([edge(n + 2, n + 1, 3), edge(n + 1, n, 3), edge(n + 3, n + 2, 3), edge(n, n + 3, 3)]);
        g.edges.extend([edge(n + 4, n + 5, 1), edge(n + 5, n + 6, 2)]);
        g.edges.extend([edge(n + 7, n + 8, 3), edge(n + 9, n + 8, 3), edge(n + 9, n + 7, 3), edge(n + 7, n + 10, 3)]);
        let snakes = decompose(&g);
        let mut want: Vec<_> = g.edges.iter().map(|e| (e.a.min(e.b), e.a.max(e.b))).collect();
        want.sort();
        assert_eq!(edge_set(&snakes), want);
        let got: Vec<_> = snakes[4..].iter().map(|s| (s.level, s.closed, s.vertices.clone())).collect();
        let want = vec![
            (3, true, vec![n, n + 1, n + 2, n + 3, n]),
            (1, false, vec![n + 4, n + 5]),
            (2, false, vec![n + 5, n + 6]),
            (3, false, vec![n + 7, n + 8, n + 9, n + 7]),
            (3, false, vec![n + 7, n + 10]),
        ];
        assert_eq!(got, want);
        assert!(snakes[..4].iter().all(|s| s.vertices.len() == 7 && s.vertices[0] == 0 && !s.closed));
        let r = smooth(&g, &SnakeOptions::default());
        assert_ends_fixed(&g, &r);
        assert!(r.converged && r.energy_after < r.energy_before);
    }

    #[test]
    fn degenerate_inputs_do_not_panic() {
        let empty = StreetGraph::default();
        let one = StreetGraph { positions: vec![[0.0, 0.0], [1.0, 0.0]], edges: vec![edge(0, 1, 1)] };
        let dup = StreetGraph {
            positions: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
            edges: vec![edge(0, 1, 1), edge(1, 0, 3), edge(1, 1, 1), edge(1, 2, 1), edge(0, 1, 1), edge(2, 9, 1)],
        };
        let same = StreetGraph { positions: vec![[2.0, 2.0]; 3], edges: vec![edge(0, 1, 1), edge(1, 2, 1)] };
        for g in [&empty, &one, &dup, &same] {
            for r in [smooth(g, &SnakeOptions::default()), fair(g, &FairOptions::default())] {
                assert!(r.energy_after.is_finite());
                assert_ends_fixed(g, &r);
            }
        }
        assert!(decompose(&empty).is_empty());
        assert_eq!(smooth(&one, &SnakeOptions::default()).snakes[0].points.len(), 5);
        assert_eq!(edge_set(&decompose(&dup)), vec![(0, 1), (1, 2)]);
    }

    #[test]
    fn energy_decreases_ends_fixed() {
        for g in [staircase(4, 1), ring()] {
            for r in [smooth(&g, &SnakeOptions::default()), fair(&g, &FairOptions::default())] {
                assert!(r.energy_after < 0.5 * r.energy_before, "{} {}", r.energy_after, r.energy_before);
                assert!(r.converged);
                assert_ends_fixed(&g, &r);
                let pts = &r.snakes[0].points;
                assert_eq!(pts.len(), 8 * 4 + 1);
                assert!(pts[4] != g.positions[1], "the corner moved");
            }
        }
    }

    #[test]
    fn straight_snake_stays_straight() {
        let (o, d) = ([3.0, -2.0], [0.6, 0.8]);
        let positions = [0.0, 1.0, 3.0, 3.5, 6.0].map(|t| [o[0] + t * d[0], o[1] + t * d[1]]).to_vec();
        let g = StreetGraph { positions, edges: (0..4).map(|i| edge(i, i + 1, 3)).collect() };
        for r in [smooth(&g, &SnakeOptions::default()), fair(&g, &FairOptions::default())] {
            assert_ends_fixed(&g, &r);
            assert!(r.snakes[0].points.iter().all(|p| cross(o, g.positions[4], *p).abs() < 1e-9));
        }
    }

    #[test]
    fn junctions_fixed_and_tangents_kept() {
        for g in [star(4), star(3)] {
            let free = SnakeOptions { junction_tangents: false, ..SnakeOptions::default() };
            let runs = [smooth(&g, &SnakeOptions::default()), fair(&g, &FairOptions::default()), smooth(&g, &free)];
            for (k, r) in runs.iter().enumerate() {
                assert_ends_fixed(&g, r);
                assert!(r.energy_after < r.energy_before);
                for s in &r.snakes {
                    assert_eq!(s.vertices[0], 0, "arms start at the centre");
                    let off = cross([0.0; 2], g.positions[s.vertices[1] as usize], s.points[1]).abs();
                    if k < 2 {
                        assert!(off < 1e-12, "point next to the junction left the edge line: {off}");
                    } else {
                        assert!(off > 1e-3, "without the constraint the staircase arm bends");
                    }
                }
            }
        }
    }

    #[test]
    fn transformed_input_gives_transformed_output() {
        let g = star(3);
        let map = |p: &P| [7.0 + 2.5 * p[0], -3.0 + 2.5 * p[1]];
        let h = StreetGraph { positions: g.positions.iter().map(map).collect(), edges: g.edges.clone() };
        let (so, fo) = (SnakeOptions::default(), FairOptions::default());
        for (a, b) in [(smooth(&g, &so), smooth(&h, &so)), (fair(&g, &fo), fair(&h, &fo))] {
            assert!((a.energy_after - b.energy_after).abs() < 1e-9 * a.energy_after);
            for (s, t) in a.snakes.iter().zip(&b.snakes) {
                assert!(s.points.iter().zip(&t.points).all(|(p, q)| dist(map(p), *q) < 1e-6));
            }
        }
    }

    /// After `fair`, the gradient at free points is zero: the linear solve is exact.
    #[test]
    fn fair_solves_exactly() {
        let opts = FairOptions { iterations: 3, ..FairOptions::default() };
        let w = SnakeWeights { tension: 0.0, stiffness: opts.fairness, inertia: opts.closeness };
        for g in [staircase(5, 1), ring(), star(4)] {
            let (t, res) = (Topology::new(&g), fair(&g, &opts));
            for (s, out) in chains(&g, &t).iter().zip(&res.snakes) {
                let mut work = Work::new(&g, &t, s, opts.subdivisions, true, t.length_scale(&g));
                let ts = terms(work.q.len(), s.closed, &scaled(w, opts.subdivisions));
                let (o, l) = (work.origin, work.scale);
                work.q = out.points[..work.q.len()].iter().map(|p| [(p[0] - o[0]) / l, (p[1] - o[1]) / l]).collect();
                let mut grad = vec![[0.0; 2]; work.q.len()];
                gradient(&ts, &work.q, &work.q0, &mut grad);
                for (gi, d) in grad.iter().zip(&work.dofs) {
                    assert!(*d != Dof::Free || dot(*gi, *gi).sqrt() < 1e-8, "gradient {gi:?}");
                }
            }
        }
        // Without sliding points one iteration is exact.
        let r = fair(&staircase(5, 1), &FairOptions::default());
        assert!(r.converged && r.iterations == 1);
    }

    #[test]
    fn energy_helper_matches_definition() {
        let w = SnakeWeights { tension: 1.0, stiffness: 2.0, inertia: 3.0 };
        let (p, p0) = ([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]], [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
        // Tension 2 + 2, stiffness 2·|(0, −2)|², inertia 3·1.
        assert_eq!(energy(&p, &p0, &w, false), 4.0 + 8.0 + 3.0);
        // Closed triangle: tension 1 + 2 + 1, stiffness 2·(2 + 5 + 5).
        let tri = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];
        assert_eq!(energy(&tri, &tri, &w, true), 4.0 + 24.0);
    }

    /// Descent reaches the exact minimiser (found by the banded solve, tension included).
    #[test]
    fn smooth_reaches_the_minimiser() {
        for level in [1, 3] {
            let (g, o) = (staircase(3, level), SnakeOptions::default());
            let t = Topology::new(&g);
            let mut work = Work::new(&g, &t, &chains(&g, &t)[0], o.subdivisions, true, t.length_scale(&g));
            let ts = terms(work.q.len(), false, &scaled(o.weights_for(level), o.subdivisions));
            solve_free(&mut work, &ts);
            let r = smooth(&g, &o);
            assert!(r.converged);
            assert!(r.snakes[0].points.iter().zip(work.points()).all(|(p, q)| dist(*p, q) < 1e-3));
            // The paper's plain descent also lowers the energy, more slowly.
            let plain = smooth(&g, &SnakeOptions { momentum: false, max_iterations: 200, ..o });
            assert!(plain.energy_after < 0.5 * plain.energy_before && plain.energy_after > r.energy_after);
        }
    }
}
