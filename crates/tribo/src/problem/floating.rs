//! Bodies held only by the contact: a piece of the mesh that its supports leave free to move rigidly (a
//! punch pushed down by a load, a block resting on a foundation) is held by the contact forces alone.
//!
//! # The formulation
//! Let the free rigid motions of such pieces be the columns of R (each a displacement of all 2N dofs,
//! `fem/rigid_motions.rs`). A = K − G is singular along R (a rigid motion has no stress, so
//! neither K nor the stabilization term sees it). The problem holds R with pins ([`crate::Dofs`]):
//! as many conditions `u_i · a = 0` as free motions, off the contact sides, which make the factorized
//! A_p positive definite. A displacement is then `u = u_p + R α`: u_p the pinned answer, α the rigid
//! motion. For a load that the piece's contact forces balance, `Rᵀ (f − Eᵀ λ) = 0`, the pins carry no
//! force, so `u_p = A_p⁻¹ (f − Eᵀ λ)` is an exact solution of `A u = f − Eᵀ λ`: the residual of A_p's
//! solve lies on the pinned rows only, and Rᵀ of it vanishes with R's pinned rows of full rank.
//!
//! The Γ_C QP of [`crate::qp`] becomes, with that equilibrium as an equality constraint,
//!
//! `min ½ λᵀ H λ + cᵀ λ  over the cone,  (E R)ᵀ λ = Rᵀ f`,
//!
//! H and c those of the pinned problem. Its Lagrange multiplier α is the rigid motion: stationarity
//! reads `H λ + c − (E R) α ∈ −N(λ)`, and `H λ + c = −(E u_p − Dγ λ − d)`, so
//! `−(E (u_p + R α) − Dγ λ − d) ∈ −N(λ)`: the contact conditions of (3.2) for `u = u_p + R α`, the
//! unpinned problem's displacement. `E R` has no stabilization part (σ(R) = 0).
//!
//! clarabel solves it ([`crate::qp::BoxQp::with_equality`]) on the whole Γ_C, and its equality duals give
//! α. The contact must be able to hold every free motion: without friction, the normal rows of E R must
//! have full rank (a body free to slide along a frictionless contact is a mechanism); with friction,
//! E R must. A load the contact cannot balance (one that pulls the body off, or a tangential load above
//! what friction holds) leaves the QP infeasible: its status says so.

use crate::error::{Error, Result};
use crate::problem::load_case::RigidLoad;
use crate::problem::Problem;

impl Problem {
    /// `E R` (2q × r, column-major) and `Rᵀ f` for the load `f_full` (2N) of the free rigid motions R
    /// of the pieces held only by the contact; empty when the supports hold every piece.
    pub(crate) fn rigid_load(&self, f_full: &[f64]) -> RigidLoad {
        if self.dofs.floating.is_empty() {
            return RigidLoad::default();
        }
        let fields = self.dofs.rigid_fields(&self.mesh);
        // σ(R) = 0: E R is the mortar part alone, whatever γ0.
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let e_r = fields.iter().flat_map(|field| self.e_action(0.0, field)).collect();
        let load = fields.iter().map(|field| dot(field, f_full)).collect();
        RigidLoad { e_r, load }
    }

    /// Checks that the contact can hold every free rigid motion: `E R` on the multipliers the friction
    /// law uses (the normal ones, and the tangential one of each dof j where `frictional(j)`: its pair has
    /// friction) has full column rank.
    ///
    /// # Errors
    /// [`Error::HeldOnlyByContact`] naming the body and the motion the contact cannot hold.
    pub(crate) fn check_held_by_contact(&self, rigid: &RigidLoad, frictional: &dyn Fn(usize) -> bool) -> Result<()> {
        let q = self.n_multipliers();
        let rows: Vec<usize> = (0..q).chain((0..q).filter(|&j| frictional(j)).map(|j| q + j)).collect();
        let frictional = rows.len() > q;
        let what = if frictional {
            "the contact line cannot hold it"
        } else {
            "frictionless contact cannot hold it (it only pushes along the normal)"
        };
        self.unseen_motion(rigid, &rows, what)
    }

    /// Checks that the contact forces `lambda` (2q) determine the rigid motion: the rows of `E R` where
    /// they act, the normal rows where λ_n > `noise` and the tangential rows where `|λ_t|` is below its
    /// bound by more than `noise` (sticking), have full column rank. Otherwise any motion along the
    /// missing direction that keeps those contacts is an answer too (a body nothing presses against the
    /// contact moves off it by any amount).
    ///
    /// # Errors
    /// [`Error::HeldOnlyByContact`] naming the body and the undetermined motion.
    pub(crate) fn check_rigid_motion_determined(
        &self,
        rigid: &RigidLoad,
        lambda: &[f64],
        bound: Option<&[f64]>,
        noise: f64,
    ) -> Result<()> {
        let q = self.n_multipliers();
        let mut rows: Vec<usize> = (0..q).filter(|&j| lambda[j] > noise).collect();
        if let Some(b) = bound {
            rows.extend((0..q).filter(|&j| lambda[j] > noise && lambda[q + j].abs() < b[j] - noise).map(|j| q + j));
        }
        self.unseen_motion(
            rigid,
            &rows,
            "nothing presses it against the contact along that motion, so its position is undetermined",
        )
    }

    /// [`Error::HeldOnlyByContact`] (with `what`) for a combination of the free motions that the rows
    /// `rows` of `E R` do not see: an eigenvalue of their Gram matrix below `16 (rows + 1) ε` times the
    /// largest column norm² of the whole `E R` (each entry is a sum of that many rounded products).
    fn unseen_motion(&self, rigid: &RigidLoad, rows: &[usize], what: &str) -> Result<()> {
        let r = rigid.load.len();
        if r == 0 {
            return Ok(());
        }
        let two_q = 2 * self.n_multipliers();
        let e_r = |k: usize, i: usize| rigid.e_r[k * two_q + i];
        let full = (0..r).map(|k| (0..two_q).map(|i| e_r(k, i).powi(2)).sum::<f64>()).fold(0.0, f64::max);
        let tiny = 16.0 * (rows.len() + 1) as f64 * f64::EPSILON * full;
        let (_, missed) = crate::linalg::gram_split(r, rows, e_r, |_| tiny);
        let Some(v) = missed.first() else {
            return Ok(());
        };
        let (body, motion) = self.describe_combination(v);
        Err(Error::HeldOnlyByContact { body, motion, what: what.to_string() })
    }

    /// The body and the words for the free motion that dominates the combination `v` of all free motions.
    fn describe_combination(&self, v: &[f64]) -> (String, String) {
        let largest = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let (mut offset, mut out) = (0, (String::new(), String::new()));
        for piece in &self.dofs.floating {
            let m = piece.motions.len();
            if let Some(j) = (offset..offset + m).find(|&j| v[j].abs() >= largest * (1.0 - 1e-12)) {
                let node = piece.nodes[0];
                let name = self.bodies.iter().find(|b| b.nodes.contains(&node)).map(|b| b.name.clone());
                out = (name.unwrap_or_default(), piece.describe(j - offset));
            }
            offset += m;
        }
        out
    }
}
