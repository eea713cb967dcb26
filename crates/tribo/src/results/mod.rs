//! Results of a solve: fields as plain vectors ([`Solution`]), the contact state per multiplier dof, the
//! discrete KKT residuals of (3.1) ([`KktResiduals`]) and a report of how the solve ended ([`Report`],
//! [`SolveStatus`]).

mod kkt;
mod solution;
mod status;

pub use kkt::KktResiduals;
pub use solution::Solution;
pub use status::{ContactState, Report, SolveStatus, Timings};
