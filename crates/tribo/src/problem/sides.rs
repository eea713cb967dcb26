//! Several contact pairs in one problem: a body pressed by a punch onto a foundation, a disc between two
//! platens, a body touching two obstacles at once.
//!
//! The first pair is the problem's own (`spec.contact` against `spec.obstacle`, or the secondary side of two
//! bodies); each further pair ([`PairSpec`]) is another contact side of the body (of either body) against its own
//! rigid obstacle, with its own multiplier mesh T_H^k and its own Coulomb μ ([`ContactSide`]). Nothing couples the
//! pairs but the body: the multipliers of pair k test only pair k's side, so every Γ_C matrix of the method is block
//! diagonal over the pairs,
//!
//! ```text
//! λ = (λ_n¹, …, λ_nᵐ, λ_t¹, …, λ_tᵐ),   E = [E_n¹; …; E_nᵐ; E_t¹; …; E_tᵐ],   Dγ = diag(Dγᵏ),   −G = Σ_k −Gᵏ,
//! ```
//!
//! and the QP (3.2) over the stacked multipliers is the one of the pairs together: its bounds and its friction
//! thresholds act dof by dof, each on its own pair's multipliers. Every solve method takes it as it takes one
//! pair. Two pairs share no edge (nor an edge set); a triangle whose edges lie on two pairs' sides (a corner)
//! carries both pairs' terms of G, so its bound on γ0 ([`crate::contact::gamma0`]) is the harmonic sum of theirs.

use crate::contact::gamma0::{edge_bounds, Gamma0Bound};
use crate::contact::mortar::MortarMatrices;
use crate::contact::multiplier::{MultiplierMesh, MultiplierPoints, MultiplierSpace};
use crate::contact::obstacle::{Obstacle, ObstacleShape};
use crate::contact::operators::ContactStress;
use crate::contact::pair::PrimarySide;
use crate::contact::ContactBoundary;
use crate::error::{check_setting, Error, Result};
use crate::fem::elasticity::{MaterialField, Model};
use crate::fem::supports::Dofs;
use crate::mesh::Mesh;
use crate::problem::Problem;
use crate::settings::friction::{Friction, FrictionLaw};

/// A further contact pair of a problem: a contact edge set of the body against its own rigid obstacle.
#[derive(Debug, Clone)]
pub struct PairSpec {
    /// Name of the contact edge set (the pair's name in the outputs).
    pub contact: String,
    /// Its rigid obstacle (shape, approach δ, shift s; a turned one is placed once).
    pub obstacle: Obstacle,
    /// Points of its multiplier mesh (the space is the problem's, `spec.multiplier_space`).
    pub multiplier_points: MultiplierPoints,
    /// Its own Coulomb coefficient μ (None: the law's, [`Friction::Coulomb`]); it needs Coulomb friction.
    pub mu: Option<f64>,
}

impl PairSpec {
    /// The edge set `contact` against `obstacle`, T_H on its FE edges.
    pub fn new(contact: impl Into<String>, obstacle: Obstacle) -> Self {
        Self { contact: contact.into(), obstacle, multiplier_points: MultiplierPoints::default(), mu: None }
    }

    /// This pair with its own Coulomb coefficient μ.
    pub fn with_mu(mut self, mu: f64) -> Self {
        self.mu = Some(mu);
        self
    }

    /// A pair from the keywords of the bindings: its edge set, its obstacle's shape (flat by default), approach and
    /// shift (0 by default), its own μ (the law's by default), and the first pair's multiplier points where they
    /// are not tied to that side ([`MultiplierPoints::for_another_side`]).
    pub fn from_keywords(
        contact: String,
        shape: Option<ObstacleShape>,
        (approach, shift): (Option<f64>, Option<f64>),
        mu: Option<f64>,
        first: &MultiplierPoints,
    ) -> Self {
        let obstacle = Obstacle::from_keywords(shape.unwrap_or(ObstacleShape::Flat), approach, shift, None);
        Self { contact, obstacle, multiplier_points: first.for_another_side(), mu }
    }
}

/// A further contact pair, assembled: its Γ_C, T_H, Γ_C matrices, the gap at its FE nodes and the stresses the
/// stabilization reads on its edges.
#[derive(Debug, Clone)]
pub struct ContactSide {
    /// The pair's name (its contact edge set).
    pub name: String,
    /// Its obstacle, as given ([`Obstacle::placed`] turns it).
    pub obstacle: Obstacle,
    /// Its Γ_C.
    pub contact: ContactBoundary,
    /// Its T_H.
    pub multipliers: MultiplierMesh,
    /// Its Γ_C matrices.
    pub mortar: MortarMatrices,
    /// The gap `g₀ − δ` at its FE nodes.
    pub gap: Vec<f64>,
    /// σ_n(v), σ_t(v) on its edges.
    pub stress: ContactStress,
    /// Its own Coulomb coefficient (None: the law's).
    pub mu: Option<f64>,
}

/// One pair's parts, borrowed: the first pair's from the problem's own fields, the others' from their
/// [`ContactSide`].
#[derive(Debug, Clone, Copy)]
pub struct PairParts<'a> {
    /// The pair's name (its contact edge set).
    pub name: &'a str,
    /// Its obstacle (as the problem was given it: [`Obstacle::placed`] turns it).
    pub obstacle: &'a Obstacle,
    /// Its Γ_C.
    pub contact: &'a ContactBoundary,
    /// Its T_H.
    pub multipliers: &'a MultiplierMesh,
    /// Its Γ_C matrices.
    pub mortar: &'a MortarMatrices,
    /// The gap at its FE nodes.
    pub gap: &'a [f64],
    /// σ_n(v), σ_t(v) on its edges.
    pub stress: &'a ContactStress,
    /// The primary side of a two-body pair (the first pair only).
    pub primary: Option<&'a PrimarySide>,
    /// Its own Coulomb coefficient (None: the law's; the first pair's is the law's).
    pub mu: Option<f64>,
}

impl ContactSide {
    /// Builds pair `pair` on `mesh` (the problem's supports `dofs`, the stiffness's `materials`): every pair's, the
    /// first's too ([`Problem`] keeps its parts in its own fields).
    ///
    /// # Errors
    /// An unknown or broken edge set, an edge on Γ_D, a side clamped everywhere or on the axis, a bad obstacle or
    /// multiplier points, a bad μ.
    pub(crate) fn new(
        mesh: &Mesh,
        model: Model,
        materials: &impl MaterialField,
        mixed: bool,
        dofs: &Dofs,
        pair: &PairSpec,
        space: MultiplierSpace,
    ) -> Result<Self> {
        pair.obstacle.validate()?;
        if let Some(mu) = pair.mu {
            check_setting("mu", mu, mu >= 0.0, "a pair's friction coefficient must be ≥ 0")?;
        }
        let mut contact = ContactBoundary::new(mesh, &pair.contact)?;
        // The obstacle as the contact meets it: turned, where it turns.
        let placed = pair.obstacle.placed();
        contact.orient_to(&placed.shape)?;
        // The gap at the nodes of Γ_C: every value the solver and its results use is checked.
        let gap = contact.node_xi.iter().map(|&xi| placed.gap(&contact, xi)).collect::<Result<Vec<f64>>>()?;
        for e in &contact.edges {
            if dofs.edges.contains(&[e.left.min(e.right), e.left.max(e.right)]) {
                return Err(Error::ContactOverlapsDirichlet { set: pair.contact.clone(), a: e.left, b: e.right });
            }
        }
        if contact.nodes.iter().all(|&node| matches!(dofs.nodes[node], crate::fem::supports::NodeSupport::Fixed { .. }))
        {
            return Err(Error::ContactFullyClamped { set: pair.contact.clone() });
        }
        // A contact edge on the axis is a line of the solid, not a surface: it has no area to press.
        let on_axis = |i: usize| dofs.axis.binary_search(&i).is_ok();
        if let Some(e) = contact.edges.iter().find(|e| model.is_axisymmetric() && on_axis(e.left) && on_axis(e.right)) {
            let what = format!(
                "the contact edge ({}, {}) of '{}' lies on the axis (r = 0): a line of the solid, with no surface to \
                 touch",
                e.left, e.right, pair.contact
            );
            return Err(Error::BadAxisymmetry { what });
        }
        let multipliers = MultiplierMesh::new(&contact, &pair.multiplier_points, space)?;
        let h_t: Vec<f64> = contact.edges.iter().map(|e| mesh.diameter(e.triangle)).collect();
        let mortar = MortarMatrices::new(&contact, &multipliers, &h_t, &placed, model)?;
        let stress = ContactStress::new(mesh, model, materials, &contact, mixed);
        Ok(Self {
            name: pair.contact.clone(),
            obstacle: pair.obstacle.clone(),
            contact,
            multipliers,
            mortar,
            gap,
            stress,
            mu: pair.mu,
        })
    }
}

impl Problem {
    /// The contact pairs, the problem's own first.
    pub fn pairs(&self) -> Vec<PairParts<'_>> {
        let first = PairParts {
            name: &self.spec.contact,
            obstacle: &self.spec.obstacle,
            contact: &self.contact,
            multipliers: &self.multipliers,
            mortar: &self.mortar,
            gap: &self.contact_gap,
            stress: &self.contact_stress,
            primary: self.primary.as_ref(),
            mu: None,
        };
        let further = self.sides.iter().map(|s| PairParts {
            name: &s.name,
            obstacle: &s.obstacle,
            contact: &s.contact,
            multipliers: &s.multipliers,
            mortar: &s.mortar,
            gap: &s.gap,
            stress: &s.stress,
            primary: None,
            mu: s.mu,
        });
        std::iter::once(first).chain(further).collect()
    }

    /// The displacement the contact law reads at every pair's FE nodes of Γ_C, stacked (the first pair's first): the
    /// jump between two bodies on the first pair's side ([`Problem::contact_displacement`]), `u` itself on the others.
    pub fn contact_displacements(&self, u: &[f64]) -> Vec<[f64; 2]> {
        let first = (0..self.contact.nodes.len()).map(|i| self.contact_displacement(i, u));
        let further =
            self.sides.iter().flat_map(|s| s.contact.nodes.iter().map(|&node| [u[2 * node], u[2 * node + 1]]));
        first.chain(further).collect()
    }

    /// The tangent at every pair's FE nodes of Γ_C, stacked as [`Problem::contact_displacements`].
    pub fn contact_node_tangents(&self) -> Vec<[f64; 2]> {
        let pairs = self.pairs();
        pairs.iter().flat_map(|p| (0..p.contact.nodes.len()).map(|i| p.contact.node_tangent(i))).collect()
    }

    /// Where each pair's multiplier dofs start among the q of one component (one more entry: q).
    pub fn pair_offsets(&self) -> Vec<usize> {
        offsets(self.pairs().iter().map(|p| p.multipliers.n_dofs()))
    }

    /// Where each pair's FE nodes of Γ_C start in the nodal fields of Γ_C (one more entry: their number).
    pub fn pair_node_offsets(&self) -> Vec<usize> {
        offsets(self.pairs().iter().map(|p| p.contact.nodes.len()))
    }

    /// Where each pair's FE edges of Γ_C start in the edge fields of Γ_C (one more entry: their number).
    pub fn pair_edge_offsets(&self) -> Vec<usize> {
        offsets(self.pairs().iter().map(|p| p.contact.n_edges()))
    }

    /// The friction law as it is solved and, for Coulomb, the coefficient μ at each of the q multiplier dofs (empty
    /// for the other laws): the first pair's is the law's μ, a further pair's its own ([`PairSpec::mu`]) or the
    /// law's. Coulomb is solved as frictionless only where every pair's μ is 0 ([`Friction::normalized`]).
    ///
    /// # Errors
    /// [`Error::SeveralPairs`] for a pair's own μ under a law other than Coulomb.
    pub(crate) fn friction_as_solved(&self, friction: &Friction) -> Result<(Friction, Vec<f64>)> {
        let (pairs, offsets) = (self.pairs(), self.pair_offsets());
        let Friction::Coulomb { mu } = *friction else {
            return match pairs.iter().find(|p| p.mu.is_some()) {
                Some(p) => Err(Error::SeveralPairs {
                    pair: p.name.to_string(),
                    what: format!("its own mu needs Coulomb friction; the law is {}", friction.law()),
                }),
                None => Ok((friction.normalized(), Vec::new())),
            };
        };
        let own = |p: &PairParts<'_>| p.mu.unwrap_or(mu);
        if pairs.iter().all(|p| own(p) == 0.0) {
            return Ok((Friction::Frictionless, Vec::new()));
        }
        let per_dof = pairs.iter().zip(offsets.windows(2)).flat_map(|(p, w)| std::iter::repeat_n(own(p), w[1] - w[0]));
        Ok((friction.clone(), per_dof.collect()))
    }

    /// The name of the law as [`Problem::friction_as_solved`] solves `friction` here: Coulomb where the μ of some
    /// pair is positive, else as [`Friction::law`] (also where the friction is refused).
    pub(crate) fn friction_law_as_solved(&self, friction: &Friction) -> FrictionLaw {
        match self.friction_as_solved(friction) {
            Ok((Friction::Coulomb { .. }, _)) => FrictionLaw::Coulomb,
            Ok((solved, _)) => solved.law(),
            Err(_) => friction.law(),
        }
    }

    /// Triplets of `−G` over all dofs, summed over the pairs.
    pub(crate) fn minus_g_triplets(&self, gamma0: f64) -> Vec<faer::sparse::Triplet<usize, usize, f64>> {
        let pairs = self.pairs();
        let further: usize = pairs.iter().skip(1).map(|p| p.stress.triplet_count()).sum();
        let mut parts = pairs.iter().map(|p| p.stress.stiffness_triplets(p.mortar, gamma0));
        let mut all = parts.next().unwrap_or_default();
        all.reserve(further);
        parts.for_each(|p| all.extend(p));
        all
    }

    /// `out += −G x` over the pairs, on the dofs below `out.len()` ([`ContactStress::add_minus_g_times`]).
    pub(crate) fn add_minus_g_times(&self, gamma0: f64, x: impl Fn(usize) -> f64 + Copy, out: &mut [f64]) {
        for p in self.pairs() {
            p.stress.add_minus_g_times(p.mortar, gamma0, x, out);
        }
    }

    /// The rows of E over all dofs, stacked: the normal rows of every pair, then the tangential ones.
    pub(crate) fn coupling_rows(&self, gamma0: f64) -> Vec<Vec<(usize, f64)>> {
        let per_pair =
            self.pairs().iter().map(|p| p.stress.coupling_rows(p.contact, p.mortar, p.primary, gamma0)).collect();
        stack(per_pair)
    }

    /// The entries of `Dγ / γ0` on one component (q × q, applied to the normal and the tangential multipliers
    /// alike), block diagonal over the pairs.
    pub(crate) fn d_h_entries(&self) -> Vec<(usize, usize, f64)> {
        let (pairs, offsets) = (self.pairs(), self.pair_offsets());
        let blocks = pairs.iter().zip(&offsets);
        blocks.flat_map(|(p, &off)| p.mortar.d_h.entries.iter().map(move |&(i, j, v)| (off + i, off + j, v))).collect()
    }

    /// Builds the further pairs of `self.spec`, checks that no two sides share an edge, and bounds γ0 over them all.
    ///
    /// # Errors
    /// As [`ContactSide::new`]; [`Error::SeveralPairs`] for an edge set or an edge of two pairs (the primary side of
    /// two bodies included).
    pub(crate) fn build_sides(&mut self, materials: &impl MaterialField) -> Result<()> {
        let spec = &self.spec;
        if spec.pairs.is_empty() {
            return Ok(());
        }
        // In axisymmetry a further pair's obstacle neither turns nor shifts (a solid of revolution slides along the
        // axis only; the first pair's shift is checked edge by edge, `Problem::check_axisymmetric_shift`).
        if let Some(p) = spec.pairs.iter().find(|p| p.obstacle.rotation.is_some() || p.obstacle.shift != 0.0) {
            if spec.model.is_axisymmetric() {
                let what = format!("the obstacle of the further pair '{}' turns or shifts: it may not", p.contact);
                return Err(Error::BadAxisymmetry { what });
            }
        }
        let mixed = spec.formulation.is_mixed();
        let sides = spec
            .pairs
            .iter()
            .map(|p| ContactSide::new(&self.mesh, spec.model, materials, mixed, &self.dofs, p, spec.multiplier_space))
            .collect::<Result<Vec<_>>>()?;
        self.sides = sides;
        // Γ_N and a further pair's Γ_C must not overlap (the first pair's is checked with the problem).
        for (traction_set, _) in &self.spec.tractions {
            for &[a, b] in self.mesh.edge_set(traction_set)? {
                let on = |e: &crate::contact::ContactEdge| [e.left, e.right] == [a, b] || [e.right, e.left] == [a, b];
                if let Some(side) = self.sides.iter().find(|s| s.contact.edges.iter().any(on)) {
                    let (set, traction_set) = (side.name.clone(), traction_set.clone());
                    return Err(Error::TractionOnContact { set, traction_set, a, b });
                }
            }
        }
        let pairs = self.pairs();
        for (k, p) in pairs.iter().enumerate() {
            if let Some(first) = pairs[..k].iter().find(|q| q.name == p.name) {
                let what =
                    format!("its edge set is that of an earlier pair too ('{}'): one side, one pair", first.name);
                return Err(Error::SeveralPairs { pair: p.name.to_string(), what });
            }
        }
        let mut owner: std::collections::HashMap<[usize; 2], &str> = std::collections::HashMap::new();
        // Two bodies: the primary side is the first pair's too.
        let primary = self.primary.iter().flat_map(|p| p.boundary.edges.iter().map(move |e| (e, &p.boundary.set)));
        let primary: std::collections::HashMap<[usize; 2], &String> =
            primary.map(|(e, set)| ([e.left.min(e.right), e.left.max(e.right)], set)).collect();
        for s in &self.sides {
            if let Some((e, set)) =
                s.contact.edges.iter().find_map(|e| primary.get_key_value(&[e.left.min(e.right), e.left.max(e.right)]))
            {
                let what =
                    format!("its edge ({}, {}) is on the primary side '{set}' of the two bodies' pair", e[0], e[1]);
                return Err(Error::SeveralPairs { pair: s.name.clone(), what });
            }
        }
        for p in &pairs {
            for e in &p.contact.edges {
                if let Some(other) = owner.insert([e.left.min(e.right), e.left.max(e.right)], p.name) {
                    let what = format!("its edge ({}, {}) is on the side of '{other}' too", e.left, e.right);
                    return Err(Error::SeveralPairs { pair: p.name.to_string(), what });
                }
            }
        }
        // A triangle whose edges lie on the sides of several pairs carries the G terms of each: its bound is the
        // harmonic sum of the pairs' (each pair's the smallest of its edges' there, as for one side).
        let mut by_triangle: std::collections::BTreeMap<usize, Vec<f64>> = std::collections::BTreeMap::new();
        for p in &pairs {
            let mut own: std::collections::BTreeMap<usize, f64> = std::collections::BTreeMap::new();
            for (b, t) in edge_bounds(&self.mesh, self.spec.model, materials, p.contact) {
                own.entry(t).and_modify(|v| *v = v.min(b)).or_insert(b);
            }
            own.into_iter().for_each(|(t, b)| by_triangle.entry(t).or_default().push(b));
        }
        let combined = by_triangle.into_iter().map(|(t, b)| (1.0 / b.iter().map(|b| 1.0 / b).sum::<f64>(), t));
        let (value, triangle) = combined.fold((f64::INFINITY, 0), |best, cur| if cur.0 < best.0 { cur } else { best });
        self.gamma0_bound = Gamma0Bound { value, triangle };
        Ok(())
    }
}

/// `[0, a, a + b, …]` of the counts.
fn offsets(counts: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut out = vec![0];
    for c in counts {
        out.push(out[out.len() - 1] + c);
    }
    out
}

/// Stacks per-pair vectors of 2q_k entries (normal then tangential) into the problem's: the normal entries of
/// every pair, then the tangential ones.
pub(crate) fn stack<T: Clone>(per_pair: Vec<Vec<T>>) -> Vec<T> {
    let halves: Vec<(&[T], &[T])> = per_pair.iter().map(|v| v.split_at(v.len() / 2)).collect();
    let normal = halves.iter().flat_map(|(n, _)| n.iter().cloned());
    let tangential = halves.iter().flat_map(|(_, t)| t.iter().cloned());
    normal.chain(tangential).collect()
}

/// The part of pair k's multipliers in a stacked vector of 2q (`offsets` from [`Problem::pair_offsets`]): its
/// normal then its tangential entries.
pub fn pair_slice<T: Clone>(stacked: &[T], offsets: &[usize], k: usize) -> Vec<T> {
    let q = offsets[offsets.len() - 1];
    let (a, b) = (offsets[k], offsets[k + 1]);
    stacked[a..b].iter().chain(&stacked[q + a..q + b]).cloned().collect()
}

#[cfg(test)]
mod tests {
    use crate::fem::mixed::Formulation;
    use crate::{graded_rectangle, Grading, Material, Problem, ProblemSpec, Side};

    /// `−G x` formed one stress component at a time is the product with the triplets of −G, for the plain and the
    /// mixed formulation (whose stress terms read the pressures, dofs beyond the displacements' 2N), and it leaves
    /// the dofs beyond `out` alone.
    #[test]
    fn minus_g_times_is_the_triplets_product() {
        for formulation in [Formulation::Displacement, Formulation::Mixed] {
            let grading = Grading { side: Side::Top, segment: [-0.3, 0.3], h_min: 0.05, h_max: 0.5, growth: 0.3 };
            let mesh = graded_rectangle([-1.0, 1.0], [-1.0, 0.0], &grading).expect("valid mesh");
            let spec = ProblemSpec::new(Material { young: 10.0, poisson: 0.45 }, "top")
                .clamped(["bottom"])
                .approach(0.01)
                .formulation(formulation);
            let problem = Problem::new(mesh, spec).expect("valid problem");
            let all = 3 * problem.mesh.n_nodes();
            let x = |d: usize| ((d * 7919) % 101) as f64 / 50.0 - 1.0;
            let triplets = problem.minus_g_triplets(0.7);
            assert!(!triplets.is_empty());
            for len in [all, 2 * problem.mesh.n_nodes()] {
                let mut expected = vec![1.0; len];
                for t in triplets.iter().filter(|t| t.row < len) {
                    expected[t.row] += t.val * x(t.col);
                }
                let mut out = vec![1.0; len];
                problem.add_minus_g_times(0.7, x, &mut out);
                let scale = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (a, b) in out.iter().zip(&expected) {
                    assert!((a - b).abs() <= 1e-13 * scale, "{a} against {b} ({formulation:?})");
                }
                assert!(out.iter().zip(&expected).any(|(a, _)| *a != 1.0), "G touches some dof");
            }
        }
    }
}
