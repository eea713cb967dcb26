//! The finite element side of the body: P1 elasticity (plane strain or stress) element by element ([`elasticity`],
//! and the axisymmetric element with its hoop strain, [`axisymmetric`]:
//! B, the element stiffness, loads, stresses, internal forces), the global assembly on the unknowns
//! ([`assemble`]), the mixed displacement–pressure formulation for ν → ½ ([`mixed`]), the
//! Dirichlet conditions ([`supports`]:
//! clamps, rollers, prescribed displacements, combined per node), the unknowns they leave
//! (`dofs`: `u = T x + ū`) and the check that they hold every piece (`rigid_motions`).

pub mod assemble;
pub mod axisymmetric;
mod dofs;
pub mod elasticity;
pub mod mixed;
mod rigid_motions;
pub use rigid_motions::FreeMotions;
pub mod supports;
