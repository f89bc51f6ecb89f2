//! The solver-neutral MILP model, its validation and the independent feasibility checker.

pub mod check;
pub mod ext_f64;
pub mod model;
pub mod numeric;
pub mod screen;
pub mod validate;

pub use check::{check_point, objectives_agree, CheckReport, Tolerances, Violation};
pub use model::{row_kind, Model, RowId, RowKind, RowView, Sense, VarId, VarKind, Variable};
pub use numeric::{numeric_screen, NumericLimits, NumericReport};
pub use screen::{screen, Infeasibility, InfeasibilityKind};
pub use validate::{Location, ModelError, ModelErrorKind, ModelStats};
