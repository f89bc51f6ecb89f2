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

/// A row without coefficients that must be ≥ 1 (issue 13: HiGHS called it optimal): no columns
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
