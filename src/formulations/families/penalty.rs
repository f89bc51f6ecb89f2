//! The indicator of a penalised configuration (13)–(14), shared by the local-configuration and
//! T-junction families (not a family).

use crate::formulations::expr::Expr;
use crate::formulations::family::Ctx;
use crate::milp::VarId;
use crate::spec::switch;

/// The indicator `Z` of a penalised configuration whose `n` terms sum to `ex` (`n` when the
/// configuration is whole), with `λ·Z` in the objective. The paper's (13)–(14): `Z` binary and
/// `0 ≤ ex − n·Z ≤ n − 1`. With the `continuous_indicators` switch: `Z ∈ [0, 1]` continuous and
/// `ex − Z ≤ n − 1` alone — exact, since `λ > 0` makes `Z = max(0, ex − (n − 1))` at an optimum,
/// 0 or 1 when the edges are integral; and stronger (`Z ≥ ex − (n − 1)` against `Z ≥ (ex −
/// (n − 1))/n`). Measured on Fig. 2e (HiGHS, 2 threads): proven in 14 s instead of a 0.08 % gap
/// at the paper's 74 s (docs/benchmarks.md).
pub fn penalty_row(c: &mut Ctx, var: String, row: String, mut ex: Expr, n: f64, lambda: f64) -> VarId {
    if c.recipe.on(&switch::CONTINUOUS_INDICATORS) {
        let z = c.em.model.add_continuous(var, 0.0, 1.0, lambda);
        ex.add(z, -1.0);
        c.em.le(row, &ex, n - 1.0);
        return z;
    }
    let z = c.em.model.add_binary(var, lambda);
    ex.add(z, -n);
    c.em.row(row, 0.0, &ex, n - 1.0);
    z
}
