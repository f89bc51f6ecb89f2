//! Small models with known answers, shared by the conformance suite.

use netspec::milp::{Model, Sense, VarId};

const INF: f64 = f64::INFINITY;

/// max 3x + 2y  s.t. x + y ≤ 4, x + 3y ≤ 6, 0 ≤ x ≤ 3, y ≥ 0  →  x = 3, y = 1, obj 11.
pub fn lp_max() -> Model {
    let mut m = Model::new("lp_max");
    m.sense = Sense::Maximize;
    let x = m.add_continuous("x", 0.0, 3.0, 3.0);
    let y = m.add_continuous("y", 0.0, INF, 2.0);
    m.add_le("c1", [(x, 1.0), (y, 1.0)], 4.0);
    m.add_le("c2", [(x, 1.0), (y, 3.0)], 6.0);
    m
}

/// Free variables and ≥ rows: min x + 0y s.t. x − y ≥ −3, y ≥ 1 (row), x, y free → x = −2.
pub fn lp_free_vars() -> Model {
    let mut m = Model::new("lp_free");
    let x = m.add_continuous("x", -INF, INF, 1.0);
    let y = m.add_continuous("y", -INF, INF, 0.0);
    m.add_ge("c1", [(x, 1.0), (y, -1.0)], -3.0);
    m.add_ge("c2", [(y, 1.0)], 1.0);
    m
}

/// Ranged and equality rows: min x + 2y + 3z s.t. 2 ≤ x + y ≤ 5 (ranged), y + z = 3, x ≤ 1.5,
/// all ≥ 0 → best: x = 1.5, y = 0.5, z = 2.5: 1.5 + 1 + 7.5 = 10; or y = 3, z = 0, x = 0:
/// 6 → optimum 6 (x = 0, y = 3, z = 0 satisfies 2 ≤ 3 ≤ 5).
pub fn lp_ranged_eq() -> Model {
    let mut m = Model::new("lp_ranged");
    let x = m.add_continuous("x", 0.0, 1.5, 1.0);
    let y = m.add_continuous("y", 0.0, INF, 2.0);
    let z = m.add_continuous("z", 0.0, INF, 3.0);
    m.add_row("range", 2.0, 5.0, [(x, 1.0), (y, 1.0)]);
    m.add_eq("eq", [(y, 1.0), (z, 1.0)], 3.0);
    m
}

/// A 0/1 knapsack: values 10, 13, 7, 8, 9, weights 5, 6, 3, 4, 4, capacity 12 → 10 + 9 + 8?
/// Enumerated in `knapsack_optimum`.
pub fn knapsack() -> Model {
    let (vals, wts, cap) = knapsack_data();
    let mut m = Model::new("knapsack");
    m.sense = Sense::Maximize;
    let xs: Vec<VarId> = vals.iter().enumerate().map(|(i, &v)| m.add_binary(format!("x{i}"), v)).collect();
    m.add_le("cap", xs.iter().zip(&wts).map(|(&x, &w)| (x, w)), cap);
    m
}

fn knapsack_data() -> (Vec<f64>, Vec<f64>, f64) {
    (vec![10.0, 13.0, 7.0, 8.0, 9.0, 4.0], vec![5.0, 6.0, 3.0, 4.0, 4.0, 2.0], 12.0)
}

/// The knapsack's optimum by brute force (so the test does not trust a constant either).
pub fn knapsack_optimum() -> f64 {
    let (vals, wts, cap) = knapsack_data();
    let n = vals.len();
    (0u32..1 << n)
        .filter(|s| (0..n).filter(|i| s >> i & 1 == 1).map(|i| wts[i]).sum::<f64>() <= cap)
        .map(|s| (0..n).filter(|i| s >> i & 1 == 1).map(|i| vals[i]).sum::<f64>())
        .fold(0.0, f64::max)
}

/// General integers with negative bounds: min 3a − 2b s.t. a + b ≥ 2.5, a − b ≤ 1.5,
/// a, b ∈ [−5, 5] integer. Optimum by enumeration in `general_integer_optimum`.
pub fn general_integer() -> Model {
    let mut m = Model::new("genint");
    let a = m.add_integer("a", -5.0, 5.0, 3.0);
    let b = m.add_integer("b", -5.0, 5.0, -2.0);
    m.add_ge("c1", [(a, 1.0), (b, 1.0)], 2.5);
    m.add_le("c2", [(a, 1.0), (b, -1.0)], 1.5);
    m
}

/// Brute-force optimum of [`general_integer`].
pub fn general_integer_optimum() -> f64 {
    let mut best = f64::INFINITY;
    for a in -5..=5 {
        for b in -5..=5 {
            let (a, b) = (a as f64, b as f64);
            if a + b >= 2.5 && a - b <= 1.5 {
                best = best.min(3.0 * a - 2.0 * b);
            }
        }
    }
    best
}

/// max −x + 10 (objective constant) with x ∈ [2, 5] integer, and a continuous y ∈ [0, 1] with
/// objective 0.5 tied to x by y ≤ x − 2 → x = 3, y = 1: −3 + 0.5 + 10 = 7.5 vs x = 2, y = 0: 8.
pub fn max_with_constant() -> Model {
    let mut m = Model::new("maxconst");
    m.sense = Sense::Maximize;
    m.obj_constant = 10.0;
    let x = m.add_integer("x", 2.0, 5.0, -1.0);
    let y = m.add_continuous("y", 0.0, 1.0, 0.5);
    m.add_le("link", [(y, 1.0), (x, -1.0)], -2.0);
    m
}

/// An LP with an objective constant: min −x − y + 7 s.t. x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0 →
/// the rows cross at x = 1.6, y = 1.2: −2.8 + 7 = 4.2.
pub fn lp_with_constant() -> Model {
    let mut m = Model::new("lp_const");
    m.obj_constant = 7.0;
    let x = m.add_continuous("x", 0.0, INF, -1.0);
    let y = m.add_continuous("y", 0.0, INF, -1.0);
    m.add_le("c1", [(x, 1.0), (y, 2.0)], 4.0);
    m.add_le("c2", [(x, 3.0), (y, 1.0)], 6.0);
    m
}

/// A ranged row and a free row (both sides infinite) in a MIP: max x + y s.t. 1 ≤ x − y ≤ 2,
/// a free row on x, x ∈ [0, 10] continuous, y ∈ [0, 10] integer → y ≤ x − 1 ≤ 9, so x = 10,
/// y = 9: 19. The free row must not constrain anything.
pub fn ranged_and_free_rows() -> Model {
    let mut m = Model::new("ranged_free");
    m.sense = Sense::Maximize;
    let x = m.add_continuous("x", 0.0, 10.0, 1.0);
    let y = m.add_integer("y", 0.0, 10.0, 1.0);
    m.add_row("ranged", 1.0, 2.0, [(x, 1.0), (y, -1.0)]);
    m.add_row("free", -INF, INF, [(x, 1.0), (y, 1.0)]);
    m
}

/// No variables, no rows, constant 7.
pub fn empty() -> Model {
    let mut m = Model::new("empty");
    m.obj_constant = 7.0;
    m
}

/// x + y ≥ 5 and x + y ≤ 3: an infeasible LP.
pub fn infeasible_lp() -> Model {
    let mut m = Model::new("infeas_lp");
    let x = m.add_continuous("x", 0.0, INF, 1.0);
    let y = m.add_continuous("y", 0.0, INF, 1.0);
    m.add_ge("lo", [(x, 1.0), (y, 1.0)], 5.0);
    m.add_le("hi", [(x, 1.0), (y, 1.0)], 3.0);
    m
}

/// 2x − 2y = 1 with integers: infeasible as a MIP, feasible as an LP.
pub fn infeasible_mip() -> Model {
    let mut m = Model::new("infeas_mip");
    let x = m.add_integer("x", 0.0, 10.0, 1.0);
    let y = m.add_integer("y", 0.0, 10.0, 1.0);
    m.add_eq("parity", [(x, 2.0), (y, -2.0)], 1.0);
    m
}

/// min −x s.t. x − y ≤ 1, x, y ≥ 0: unbounded.
pub fn unbounded_lp() -> Model {
    let mut m = Model::new("unbounded");
    let x = m.add_continuous("x", 0.0, INF, -1.0);
    let y = m.add_continuous("y", 0.0, INF, 0.0);
    m.add_le("c", [(x, 1.0), (y, -1.0)], 1.0);
    m
}

/// A MIP whose relaxation is unbounded through a continuous variable: min −y s.t. y − x ≥ 0.5,
/// x ∈ [0, 5] integer, y ≥ 0 continuous (no integer bound is involved, so a backend that caps
/// unbounded integers still sees the ray).
pub fn unbounded_mip() -> Model {
    let mut m = Model::new("unbounded_mip");
    let x = m.add_integer("x", 0.0, 5.0, 0.0);
    let y = m.add_continuous("y", 0.0, INF, -1.0);
    m.add_ge("c", [(y, 1.0), (x, -1.0)], 0.5);
    m
}

/// Primal and dual both infeasible: min −x − y s.t. x − y ≥ 1, −x + y ≥ 1, x, y free.
pub fn infeasible_or_unbounded() -> Model {
    let mut m = Model::new("dual_and_primal_infeasible");
    let x = m.add_continuous("x", -INF, INF, -1.0);
    let y = m.add_continuous("y", -INF, INF, -1.0);
    m.add_ge("a", [(x, 1.0), (y, -1.0)], 1.0);
    m.add_ge("b", [(x, -1.0), (y, 1.0)], 1.0);
    m
}

/// A deterministic pseudo-random generator (SplitMix64), so models are identical everywhere.
pub struct Rng(u64);

impl Rng {
    /// Seeded generator.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    /// Next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }
    /// Uniform integer in `[0, n)`.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A market-split instance (Cornuéjols & Dawande 1998): `m` equality rows over `n` binaries with
/// coefficients in [0, 99] and slack pairs charged in the objective; the all-zero point with
/// slacks is a trivial incumbent and the LP bound is 0.
///
/// With `planted`, the right-hand sides come from a random 0/1 point, so the optimum is 0 and
/// is hard to *find* (the planted point is returned as a full solution). Without, they are half
/// the row sums (the classic hard form): an exact split almost surely does not exist at
/// `m = 4, n = 30`, and proving that takes branch and bound far longer than any test limit.
pub fn market_split(m_rows: usize, n: usize, seed: u64, planted: bool) -> (Model, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let mut m = Model::new(format!("market_split_{m_rows}x{n}"));
    let xs: Vec<VarId> = (0..n).map(|j| m.add_binary(format!("x{j}"), 0.0)).collect();
    let planted_point = planted;
    let planted: Vec<f64> = (0..n).map(|_| rng.below(2) as f64).collect();
    let mut point = planted.clone();
    for i in 0..m_rows {
        let a: Vec<f64> = (0..n).map(|_| rng.below(100) as f64).collect();
        let rhs: f64 = if planted_point {
            a.iter().zip(&planted).map(|(a, x)| a * x).sum()
        } else {
            (a.iter().sum::<f64>() / 2.0).floor()
        };
        let sp = m.add_continuous(format!("sp{i}"), 0.0, INF, 1.0);
        let sm = m.add_continuous(format!("sm{i}"), 0.0, INF, 1.0);
        let terms = xs.iter().zip(&a).map(|(&x, &c)| (x, c)).chain([(sp, 1.0), (sm, -1.0)]);
        m.add_eq(format!("split{i}"), terms, rhs);
        point.push(0.0);
        point.push(0.0);
    }
    (m, point)
}

/// A multi-dimensional 0/1 knapsack with `n` items and `k` capacity rows (max), whose LP bound
/// is within a few percent of the optimum but which takes many nodes to close exactly.
pub fn multi_knapsack(n: usize, k: usize, seed: u64) -> Model {
    let mut rng = Rng::new(seed);
    let mut m = Model::new(format!("mkp_{n}x{k}"));
    m.sense = Sense::Maximize;
    let xs: Vec<VarId> = (0..n).map(|j| m.add_binary(format!("x{j}"), 0.0)).collect();
    let mut weights = vec![vec![0.0; n]; k];
    for (i, row) in weights.iter_mut().enumerate() {
        for w in row.iter_mut() {
            *w = (10 + rng.below(90)) as f64;
        }
        let cap = row.iter().sum::<f64>() / 2.0;
        m.add_le(format!("cap{i}"), xs.iter().zip(row.iter()).map(|(&x, &w)| (x, w)), cap.floor());
    }
    for (j, &x) in xs.iter().enumerate() {
        let w: f64 = weights.iter().map(|r| r[j]).sum::<f64>() / k as f64;
        m.var_mut(x).obj = (w + rng.below(20) as f64).round();
    }
    m
}

/// An edge of a tour model: its two cities and its variable.
pub type TourEdge = (usize, usize, VarId);

/// Six cities in two far-apart triangles; `x_e` per pair with the distance as cost; degree 2 at
/// every city. Returns the model, the edges (i, j, var) and the cities.
pub fn two_cluster_tour() -> (Model, Vec<TourEdge>, Vec<[f64; 2]>) {
    let cities = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.5], [10.0, 0.0], [11.0, 0.5], [10.0, 2.0]];
    let mut m = Model::new("two_cluster_tour");
    let mut edges = Vec::new();
    for i in 0..cities.len() {
        for j in i + 1..cities.len() {
            let d = dist(cities[i], cities[j]);
            edges.push((i, j, m.add_binary(format!("x_{i}_{j}"), d)));
        }
    }
    for v in 0..cities.len() {
        let terms: Vec<_> = edges.iter().filter(|&&(i, j, _)| i == v || j == v).map(|&(_, _, x)| (x, 1.0)).collect();
        m.add_eq(format!("deg_{v}"), terms, 2.0);
    }
    (m, edges, cities)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

/// The shortest tour through every city, by enumerating the tours that start at city 0.
pub fn brute_force_tour(cities: &[[f64; 2]]) -> f64 {
    fn go(cities: &[[f64; 2]], path: &mut Vec<usize>, used: &mut [bool], best: &mut f64) {
        if path.len() == cities.len() {
            let mut len = dist(cities[path[path.len() - 1]], cities[path[0]]);
            for w in path.windows(2) {
                len += dist(cities[w[0]], cities[w[1]]);
            }
            *best = best.min(len);
            return;
        }
        for c in 0..cities.len() {
            if !used[c] {
                used[c] = true;
                path.push(c);
                go(cities, path, used, best);
                path.pop();
                used[c] = false;
            }
        }
    }
    let mut used = vec![false; cities.len()];
    used[0] = true;
    let mut best = f64::INFINITY;
    go(cities, &mut vec![0], &mut used, &mut best);
    best
}

/// Subtour elimination: for every connected component `S` of the chosen edges that is not the
/// whole tour, `Σ_{e∈δ(S)} x_e ≥ 2`.
pub struct SubtourSeparator {
    /// Edges as (i, j, var).
    pub edges: Vec<(usize, usize, VarId)>,
    /// Cities.
    pub n: usize,
    /// Calls so far.
    pub calls: usize,
}

impl SubtourSeparator {
    fn labels(&self, x: &[f64]) -> Vec<usize> {
        let mut comp: Vec<usize> = (0..self.n).collect();
        fn find(c: &mut [usize], v: usize) -> usize {
            if c[v] != v {
                let r = find(c, c[v]);
                c[v] = r;
            }
            c[v]
        }
        for &(i, j, v) in &self.edges {
            if x[v.index()] > 0.5 {
                let (a, b) = (find(&mut comp, i), find(&mut comp, j));
                comp[a] = b;
            }
        }
        (0..self.n).map(|v| find(&mut comp, v)).collect()
    }

    /// Number of connected components of the chosen edges.
    pub fn components(&self, x: &[f64]) -> usize {
        let mut l = self.labels(x);
        l.sort();
        l.dedup();
        l.len()
    }
}

impl netspec::solvers::Separator for SubtourSeparator {
    fn name(&self) -> &str {
        "subtour"
    }

    fn separate_integral(&mut self, x: &[f64]) -> Vec<netspec::solvers::LazyRow> {
        let labels = self.labels(x);
        let mut roots = labels.clone();
        roots.sort();
        roots.dedup();
        if roots.len() < 2 {
            return Vec::new();
        }
        roots
            .iter()
            .map(|&r| {
                self.calls += 1;
                let terms = self
                    .edges
                    .iter()
                    .filter(|&&(i, j, _)| (labels[i] == r) != (labels[j] == r))
                    .map(|&(_, _, v)| (v, 1.0))
                    .collect();
                netspec::solvers::LazyRow {
                    name: format!("subtour{}", self.calls),
                    lhs: 2.0,
                    rhs: f64::INFINITY,
                    terms,
                }
            })
            .collect()
    }

    fn locks(&self) -> Vec<(VarId, netspec::solvers::Lock)> {
        self.edges.iter().map(|&(_, _, v)| (v, netspec::solvers::Lock::Down)).collect()
    }
}

/// A row without coefficients that must be ≥ 1 (HiGHS once called it optimal): no columns
/// at all, as in `c: >= 1` in an LP file.
pub fn empty_row_no_columns() -> Model {
    let mut m = Model::new("empty_row_no_columns");
    m.add_ge("c", [], 1.0);
    m
}

/// The same empty row beside an ordinary MIP.
pub fn empty_row_with_columns() -> Model {
    let mut m = knapsack();
    m.add_ge("empty", [], 1.0);
    m
}
