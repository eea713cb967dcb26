//! Contact on Γ_C: the boundary segment and its conventions ([`ContactBoundary`]), the rigid obstacle
//! ([`obstacle`]), the multiplier mesh T_H and its bases ([`multiplier`]), the Γ_C matrices M1–M3 and the
//! γ-weighted terms, exact on the common refinement ([`mortar`]), the Barbosa–Hughes operators `−G` and
//! `E` ([`operators`]), the admissible bound on γ0 ([`gamma0`]) and the primary side of a two-body
//! pair ([`pair`]).
//!
//! # Conventions
//! * `n` is the unit **outward** normal of the body on Γ_C and `t = (−n₂, n₁)`, as in the paper.
//!   Normal quantities (`u_n`, `σ_n`, `λ_n`) are components along `n`, tangential ones along `t`.
//! * Positions on Γ_C are given by an **abscissa** `ξ = (x − o)·d`, where `o` is the foot of the
//!   perpendicular from the world origin to the line of Γ_C and `d = ±t` is chosen so that it points
//!   toward increasing x (toward increasing y when Γ_C is vertical). On the top face of a block
//!   (`n = (0, 1)`, `t = (−1, 0)`) the abscissa is therefore simply `x`, while tangential components are
//!   along `−x`. [`ContactBoundary::tangent_sign`] is `d · t` (±1).
//! * Straightness is checked with a tolerance relative to the local edge length: a node may lie at most
//!   `√ε · h_E` off the line (coordinates rounded to about 8 significant digits still pass).
//! * A Γ_C that is not straight is a **bent** chain of edges (one body against a rigid obstacle): each edge
//!   has its own `n_e` and `t_e`, normal and tangential quantities on an edge are along its own frame, and
//!   the abscissa is the arclength ([`ContactBoundary`]'s documentation). The multipliers are scalar
//!   functions of the arclength, so a P1 λ is continuous through a kink and its components turn with the
//!   edges: the traction on edge e is `−λ_n n_e − λ_t t_e`. M1–M3 and the γ-weighted terms are 1D integrals
//!   in the arclength, unchanged; only the coupling `∫ ψ_j v·n` is summed edge by edge
//!   ([`mortar::MortarMatrices::m2_edges`]), and the stabilization reads σ(u_h) n_e on each edge. The paper's
//!   stability argument turns each edge onto the x axis by itself (it is local to an edge and its triangle),
//!   so (3.3)–(3.4) hold edge by edge, and the admissible γ0 is unchanged: `|σ n|²` does not depend on the
//!   direction of n for an isotropic material ([`gamma0`]).

mod boundary;
pub mod gamma0;
pub mod mortar;
pub mod multiplier;
mod nearest;
pub mod obstacle;
pub mod operators;
pub mod pair;

pub use crate::mesh::line::geometric_tol_rel;
pub use boundary::{ContactBoundary, ContactEdge};
