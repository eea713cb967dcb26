//! Substitutions with the LDLᵀ factor of A that visit only what a sparse right-hand side reaches and what the
//! caller reads ([`crate::linalg::blocks`]).
//!
//! # Why
//! The active-set method on the saddle-point system asks A's factor for the gap `E A⁻¹ (f − Eᵀ ν)` of its
//! certification and for `νᵀ E A⁻¹ Eᵀ ν` (diag H, the curvature along a move). Their right-hand sides live on
//! the dofs of Γ_C in contact, and E reads the displacement on Γ_C only. A full solve reads the whole factor
//! twice: on the graded Hertz mesh of 55k unknowns the forward substitution from a contact zone's dofs
//! reaches a few per cent of the factor, and the backward substitution of the dofs E reads (with everything
//! above them in the elimination tree) about three quarters.

use super::Factor;
use crate::error::Result;

impl Factor {
    /// `E u` for the displacement `u = A⁻¹ (f − Eᵀ λ)` of the multipliers λ (2q): what [`Factor::displacement`]
    /// and [`Factor::apply_e`] give, at less cost with the LDLᵀ factor of A. There the forward substitution
    /// visits only what `f − Eᵀ λ` reaches, and the backward one only the blocks holding the dofs E reads and
    /// those above them in the tree.
    ///
    /// # Errors
    /// As [`Factor::displacement`].
    pub(crate) fn e_displacement(&self, f: &[f64], lambda: &[f64]) -> Result<Vec<f64>> {
        let Some((factor, d_inv)) = self.direct.blocks() else {
            return Ok(self.apply_e(&self.displacement(f, lambda)?));
        };
        let closed = self.e_closure.get_or_init(|| factor.closure(self.e_rows.iter().flatten().map(|&(i, _)| i)));
        let rhs: Vec<f64> = f.iter().zip(self.apply_et(lambda)).map(|(fi, ei)| fi - ei).collect();
        let mut y = factor.permuted(&rhs);
        factor.forward(&mut y);
        y.iter_mut().zip(d_inv).for_each(|(yi, di)| *yi *= di);
        factor.backward_on(&mut y, closed);
        Ok(self.e_rows.iter().map(|row| row.iter().map(|&(i, v)| v * y[factor.position(i)]).sum()).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2D Laplacian-like SPD matrix on an nx × ny grid (5-point stencil plus a shift).
    fn grid(nx: usize, ny: usize) -> Result<faer::sparse::SparseColMat<usize, f64>, String> {
        let id = |i: usize, j: usize| i * ny + j;
        let mut t = Vec::new();
        for i in 0..nx {
            for j in 0..ny {
                t.push(faer::sparse::Triplet::new(id(i, j), id(i, j), 4.5 + 0.01 * ((i * 7 + j * 3) % 5) as f64));
                if i + 1 < nx {
                    t.push(faer::sparse::Triplet::new(id(i + 1, j), id(i, j), -1.0));
                    t.push(faer::sparse::Triplet::new(id(i, j), id(i + 1, j), -1.0));
                }
                if j + 1 < ny {
                    t.push(faer::sparse::Triplet::new(id(i, j + 1), id(i, j), -1.0));
                    t.push(faer::sparse::Triplet::new(id(i, j), id(i, j + 1), -1.0));
                }
            }
        }
        faer::sparse::SparseColMat::try_new_from_triplets(nx * ny, nx * ny, &t).map_err(|e| format!("{e:?}"))
    }

    /// On a simplicial and on a supernodal factor: the restricted backward substitution gives the full solve
    /// at the dofs asked for (and leaves others as they were), and the forward one alone gives `bᵀ A⁻¹ b`.
    #[test]
    fn restricted_substitutions_give_the_full_solve_where_asked() -> Result<(), String> {
        use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, SymmetricOrdering};
        use faer::sparse::linalg::SupernodalThreshold;
        let a = grid(30, 20)?;
        let n = a.nrows();
        for threshold in [SupernodalThreshold::FORCE_SIMPLICIAL, SupernodalThreshold::FORCE_SUPERNODAL] {
            let params = CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() };
            let symbolic = factorize_symbolic_cholesky(a.symbolic(), faer::Side::Lower, SymmetricOrdering::Amd, params)
                .map_err(|e| format!("{e:?}"))?;
            let (values, d_inv) =
                super::super::direct::factorize(&symbolic, a.as_ref(), 0, usize::MAX).map_err(|e| e.to_string())?;
            // The reference: faer's own solve with the factor.
            let mut x = faer::Mat::<f64>::zeros(n, 1);
            // A right-hand side on a few dofs of one edge, and the dofs of another edge asked for.
            let mut b = vec![0.0; n];
            for (k, i) in [3usize, 4, 5, 9].iter().enumerate() {
                b[*i] = 1.0 + k as f64;
                x[(*i, 0)] = b[*i];
            }
            let mut mem = faer::dyn_stack::MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, faer::Par::Seq));
            faer::sparse::linalg::cholesky::LdltRef::new(&symbolic, &values).solve_in_place_with_conj(
                faer::Conj::No,
                x.as_mut(),
                faer::Par::Seq,
                faer::dyn_stack::MemStack::new(&mut mem),
            );
            let full: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
            let direct = super::super::direct::Direct::Ldlt(std::sync::Arc::new(symbolic), values, d_inv);
            let (s, d_inv) = direct.blocks().ok_or("no LDLᵀ factor")?;
            // The whole solve by the block substitutions, as `Factor` does it for one right-hand side.
            let whole = super::super::direct::solve(&direct, &b).map_err(|e| e.to_string())?;
            let scale = full.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for i in 0..n {
                assert!((whole[i] - full[i]).abs() <= 1e-13 * scale, "{threshold:?}, dof {i}: {}", whole[i]);
            }
            let asked: Vec<usize> = (0..30).map(|i| i * 20 + 19).collect();
            let closed = s.closure(asked.iter().copied());
            let mut y = s.permuted(&b);
            s.forward(&mut y);
            y.iter_mut().zip(d_inv).for_each(|(yi, di)| *yi *= di);
            s.backward_on(&mut y, &closed);
            for &i in &asked {
                let got = y[s.position(i)];
                assert!((got - full[i]).abs() <= 1e-13 * scale, "dof {i}: {got} against {}", full[i]);
            }
            let skipped = (0..n).filter(|&i| (y[s.position(i)] - full[i]).abs() > 1e-13 * scale).count();
            assert!(skipped > 0, "{threshold:?}: the closure of one edge is the whole factor");
            // The forward substitution alone gives (L⁻¹ P b)ᵀ D⁻¹ (L⁻¹ P b) = bᵀ A⁻¹ b.
            let energy = direct.energies(faer::Mat::from_fn(n, 1, |i, _| b[i]).as_ref()).ok_or("no energies")?[0];
            let exact: f64 = b.iter().zip(&full).map(|(x, y)| x * y).sum();
            assert!((energy - exact).abs() <= 1e-13 * exact, "{energy} against {exact}");
        }
        Ok(())
    }

    /// Two paths to `E A⁻¹ (f − Eᵀ λ)` on a graded Hertz problem with a load: the restricted substitutions and
    /// the full solve followed by E.
    #[test]
    fn e_displacement_is_e_of_the_displacement() -> Result<(), String> {
        use crate::settings::Condensation;
        use crate::{
            graded_rectangle, Grading, Material, MultiplierPoints, MultiplierSpace, ObstacleShape, Problem,
            ProblemSpec, Side, Stabilization,
        };
        let grading = Grading { side: Side::Top, segment: [-0.2, 0.2], h_min: 0.01, h_max: 0.25, growth: 0.3 };
        let mesh = graded_rectangle([-2.0, 2.0], [-2.0, 0.0], &grading).map_err(|e| e.to_string())?;
        let spec = ProblemSpec::new(Material { young: 200.0, poisson: 0.3 }, "top")
            .clamped(["bottom"])
            .obstacle(ObstacleShape::Circle { center: 0.0, radius: 1.0 })
            .approach(0.01)
            .multipliers(MultiplierPoints::RatioToFe(1.0), MultiplierSpace::P1);
        let problem = Problem::new(mesh, spec).map_err(|e| e.to_string())?;
        let condensed = problem
            .condense_with(Stabilization::Fraction(0.5), Condensation::Columns, usize::MAX)
            .map_err(|e| e.to_string())?;
        let factor = condensed.factor();
        if factor.direct.blocks().is_none() {
            return Err("the factor of A is not an LDLᵀ one: the restricted path is not tested".into());
        }
        let m = 2 * condensed.q();
        // λ on a stretch of the multipliers only, as in a contact zone, and λ everywhere; with and without f.
        let zone: Vec<f64> = (0..m).map(|j| if j % (m / 2) < m / 6 { (j as f64 * 0.3).sin() } else { 0.0 }).collect();
        let everywhere: Vec<f64> = (0..m).map(|j| (j as f64 * 0.7).cos()).collect();
        let load: Vec<f64> = (0..factor.n).map(|i| ((i % 7) as f64 - 3.0) * 1e-3).collect();
        for lambda in [&zone, &everywhere] {
            for f in [&factor.f, &load] {
                let fast = factor.e_displacement(f, lambda).map_err(|e| e.to_string())?;
                let full = factor.apply_e(&factor.displacement(f, lambda).map_err(|e| e.to_string())?);
                let scale = full.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
                for (j, (a, b)) in fast.iter().zip(&full).enumerate() {
                    assert!((a - b).abs() <= 1e-12 * scale, "multiplier {j}: {a} against {b} (of {scale})");
                }
            }
        }
        Ok(())
    }
}
