//! Results of a solve: fields as plain vectors ([`Solution`]), the contact state per multiplier dof, the
//! discrete KKT residuals of (3.1) ([`KktResiduals`]) and a report of how the solve ended ([`Report`],
//! [`SolveStatus`]).

pub(crate) mod estimator;
mod gamma_c;
mod kkt;
mod pairs;
mod solution;
mod status;
mod zones;

pub use estimator::{ErrorBars, ErrorEstimate, SUBDIVISIONS};
pub use kkt::KktResiduals;
pub use pairs::PairResult;
pub use solution::Solution;
pub use status::{Agreement, ContactState, CoulombCheck, Report, Scalar, SolveStatus, Timings};
pub(crate) use zones::dof_span;
pub use zones::{loop_zone, zone, Zone};
