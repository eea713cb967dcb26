//! Mortar-type matrices on Γ_C, integrated exactly on the common refinement of the FE edges and the
//! multiplier segments (the "supermesh" of the two 1D meshes).
//!
//! Notation (paper, end of §3.2): `φ_i` are the traces on Γ_C of the P1 FE hat functions (one per Γ_C
//! node, p of them), `ψ_j` the multiplier basis functions (q of them), `χ_k` the indicators of the FE
//! edges of Γ_C (r of them), which carry σ_n(u_h) and σ_t(u_h), constant per triangle. Then
//!
//! * `M1 = ∫ φ_i φ_j` (p × p), `M2 = ∫ φ_i ψ_j` (p × q), `M3 = ∫ φ_i χ_k` (p × r);
//! * the γ-weighted terms of (3.1), with γ = γ0 h_T constant on each FE edge:
//!   `Dγ = ∫ γ ψ_i ψ_j` (q × q), `Cγ = ∫ γ ψ_j χ_k` (q × r) and `Gγ = ∫ γ χ_k χ_l = diag(γ_k |E_k|)`;
//! * `w_j = ∫ ψ_j` and the gap moments `d_j = ∫ ψ_j g` (the obstacle, see [`crate::contact::obstacle`]).
//!
//! Every integrand but the gap is a polynomial of degree ≤ 2 on each refinement piece (≤ 3 with the
//! axisymmetric measure 2π r), so 2-point Gauss–Legendre is exact; the gap moments use 4 points (exact for a
//! Hertz parabola).
//! Breakpoints of the two meshes closer than `√ε` times the smaller of the two local sizes are merged, so
//! nearly coincident points never create slivers, and the pieces tile Γ_C exactly.

use crate::contact::multiplier::MultiplierMesh;
use crate::contact::obstacle::Obstacle;
use crate::contact::ContactBoundary;
use crate::error::Result;
use crate::fem::axisymmetric::radial_weight;
use crate::fem::elasticity::Model;
use crate::mesh::line::geometric_tol_rel;

/// One piece of the common refinement: `[a, b]` inside FE edge `edge` and multiplier segment `cell`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Left abscissa.
    pub a: f64,
    /// Right abscissa.
    pub b: f64,
    /// Index of the FE edge of Γ_C.
    pub edge: usize,
    /// Index of the multiplier segment.
    pub cell: usize,
}

/// Common refinement of two partitions of the same interval (`fe` and `mult` are increasing breakpoints
/// with equal first and last values).
///
/// Every FE node is a breakpoint (exactly: the FE basis is integrated edge by edge). An interior
/// multiplier point becomes a breakpoint unless it lies within `√ε h_E` of a breakpoint already kept (h_E
/// the length of the FE edge that contains it): nearly coincident points are merged instead of creating
/// slivers. Each piece is assigned to the FE edge and the multiplier cell that contain its midpoint.
pub fn common_refinement(fe: &[f64], mult: &[f64]) -> Vec<Piece> {
    let tol = geometric_tol_rel();
    let ne = fe.len() - 1;
    let edge_of = |x: f64| fe.partition_point(|&y| y <= x).clamp(1, ne) - 1;
    let mut breaks: Vec<f64> = fe.to_vec();
    let mut extra: Vec<f64> = Vec::new();
    for &x in &mult[1..mult.len() - 1] {
        let e = edge_of(x);
        let near = tol * (fe[e + 1] - fe[e]);
        let close_to_fe = (x - fe[e]).abs() <= near || (fe[e + 1] - x).abs() <= near;
        let close_to_prev = extra.last().is_some_and(|&p| x - p <= near);
        if !close_to_fe && !close_to_prev {
            extra.push(x);
        }
    }
    breaks.extend(extra);
    breaks.sort_by(f64::total_cmp);
    let nc = mult.len() - 1;
    breaks
        .windows(2)
        .map(|w| {
            let mid = 0.5 * (w[0] + w[1]);
            let cell = mult.partition_point(|&y| y <= mid).clamp(1, nc) - 1;
            Piece { a: w[0], b: w[1], edge: edge_of(mid), cell }
        })
        .collect()
}

/// A sparse matrix as a list of `(row, col, value)` with summed duplicates, small and built once.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Coo {
    /// Number of rows.
    pub nrows: usize,
    /// Number of columns.
    pub ncols: usize,
    /// Entries, sorted by (row, column), duplicates summed.
    pub entries: Vec<(usize, usize, f64)>,
}

impl Coo {
    pub(crate) fn new(nrows: usize, ncols: usize) -> Self {
        Self { nrows, ncols, entries: Vec::new() }
    }

    pub(crate) fn compress(mut self) -> Self {
        self.entries.sort_by_key(|e| (e.0, e.1));
        let mut out: Vec<(usize, usize, f64)> = Vec::with_capacity(self.entries.len());
        for e in self.entries {
            match out.last_mut() {
                Some(l) if l.0 == e.0 && l.1 == e.1 => l.2 += e.2,
                _ => out.push(e),
            }
        }
        self.entries = out;
        self
    }

    /// Row sums.
    pub fn row_sums(&self) -> Vec<f64> {
        let mut s = vec![0.0; self.nrows];
        for &(i, _, v) in &self.entries {
            s[i] += v;
        }
        s
    }
}

/// All the Γ_C matrices of the method.
#[derive(Debug, Clone)]
pub struct MortarMatrices {
    /// `M1 = ∫ φ_i φ_j`.
    pub m1: Coo,
    /// `M2 = ∫ φ_i ψ_j`.
    pub m2: Coo,
    /// M2 edge by edge, `(i, j, k, ∫_{E_k} φ_i ψ_j)` sorted, for a Γ_C whose edges have their own contact
    /// frames (empty where they share one, [`crate::contact::ContactBoundary::one_frame`], and `m2` serves).
    pub m2_edges: Vec<(usize, usize, usize, f64)>,
    /// `M3 = ∫ φ_i χ_k`.
    pub m3: Coo,
    /// `∫ h_T ψ_i ψ_j`: multiply by γ0 for `Dγ`.
    pub d_h: Coo,
    /// `∫ h_T ψ_j χ_k`: multiply by γ0 for `Cγ`.
    pub c_h: Coo,
    /// `h_T |E_k|` per FE edge: multiply by γ0 for the diagonal of `Gγ`.
    pub g_h: Vec<f64>,
    /// `w_j = ∫ ψ_j`.
    pub psi_integrals: Vec<f64>,
    /// `∫ ψ_j g` with g the gap after the approach.
    pub gap_moments: Vec<f64>,
    /// `∫ψ_j s(ξ)` where a turned obstacle's surface moves along Γ_C by a varying s(ξ)
    /// ([`crate::contact::obstacle`]); empty otherwise (then `∫ψ_j s = s ∫ψ_j`).
    pub shift_moments: Vec<f64>,
}

pub(crate) const GAUSS2: [(f64, f64); 2] = [(-0.577_350_269_189_625_8, 1.0), (0.577_350_269_189_625_8, 1.0)];
pub(crate) const GAUSS4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    (-0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
];

impl MortarMatrices {
    /// Integrates every Γ_C matrix. `h_t[k]` is the diameter of the triangle owning FE edge k. Under
    /// [`Model::Axisymmetric`] every integral is over the surface of revolution, `2π r ds` (r linear on each
    /// edge: the integrands gain one degree and the rules stay exact).
    ///
    /// # Errors
    /// [`crate::Error::BadObstacle`] if the gap function returns a non-finite value.
    pub fn new(
        contact: &ContactBoundary,
        mult: &MultiplierMesh,
        h_t: &[f64],
        obstacle: &Obstacle,
        model: Model,
    ) -> Result<Self> {
        let fe = &contact.node_xi;
        let measure = |e: usize, x: f64| measure(contact, model, e, x);
        let (p, q, r) = (fe.len(), mult.n_dofs(), contact.n_edges());
        let pieces = common_refinement(fe, &mult.xi);
        let (mut m1, mut m2, mut m3) = (Coo::new(p, p), Coo::new(p, q), Coo::new(p, r));
        let (mut d_h, mut c_h) = (Coo::new(q, q), Coo::new(q, r));
        let mut m2_edges = Vec::new();
        let bent = !contact.one_frame;
        let g_h: Vec<f64> = contact
            .edges
            .iter()
            .zip(h_t)
            .enumerate()
            .map(|(k, (e, h))| h * e.length * measure(k, 0.5 * (fe[k] + fe[k + 1])))
            .collect();
        let mut psi_integrals = vec![0.0; q];
        let fe_basis = |e: usize, x: f64| {
            let s = (x - fe[e]) / (fe[e + 1] - fe[e]);
            [(e, 1.0 - s), (e + 1, s)]
        };
        for pc in &pieces {
            let (half, mid) = (0.5 * (pc.b - pc.a), 0.5 * (pc.a + pc.b));
            let h = h_t[pc.edge];
            for &(t, w) in &GAUSS2 {
                let x = mid + half * t;
                let w = w * half * measure(pc.edge, x);
                let phi = fe_basis(pc.edge, x);
                let (psi, npsi) = mult.basis(pc.cell, x);
                for &(i, fi) in &phi {
                    for &(j, fj) in &phi {
                        m1.entries.push((i, j, w * fi * fj));
                    }
                    for &(j, pj) in &psi[..npsi] {
                        m2.entries.push((i, j, w * fi * pj));
                        if bent {
                            m2_edges.push((i, j, pc.edge, w * fi * pj));
                        }
                    }
                    m3.entries.push((i, pc.edge, w * fi));
                }
                for &(i, pi) in &psi[..npsi] {
                    for &(j, pj) in &psi[..npsi] {
                        d_h.entries.push((i, j, w * h * pi * pj));
                    }
                    c_h.entries.push((i, pc.edge, w * h * pi));
                    psi_integrals[i] += w * pi;
                }
            }
        }
        m2_edges.sort_by_key(|e| (e.0, e.1, e.2));
        let mut by_edge: Vec<(usize, usize, usize, f64)> = Vec::with_capacity(m2_edges.len());
        for e in m2_edges {
            match by_edge.last_mut() {
                Some(l) if (l.0, l.1, l.2) == (e.0, e.1, e.2) => l.3 += e.3,
                _ => by_edge.push(e),
            }
        }
        let (gap_moments, shift_moments) = obstacle_moments(contact, mult, obstacle, model)?;
        Ok(Self {
            m1: m1.compress(),
            m2: m2.compress(),
            m2_edges: by_edge,
            m3: m3.compress(),
            d_h: d_h.compress(),
            c_h: c_h.compress(),
            g_h,
            psi_integrals,
            gap_moments,
            shift_moments,
        })
    }
}

/// The obstacle's moments on T_H: `(∫ψ_j g, ∫ψ_j s)` with the gap `g = g₀ − δ` and, where the obstacle turns, the
/// motion of its surface along each edge's tangent `s(ξ)` ([`Obstacle::tangential_motion`]; empty where it does not
/// turn: the moments are then `s ∫ψ_j`), both exact on the common refinement up to the gap's smoothness (Gauss, 4
/// points per piece). `obstacle` is placed ([`Obstacle::placed`]); a history turning it calls this per step.
///
/// # Errors
/// [`crate::Error::BadObstacle`] if the gap function returns a non-finite value.
pub fn obstacle_moments(
    contact: &ContactBoundary,
    mult: &MultiplierMesh,
    obstacle: &Obstacle,
    model: Model,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let fe = &contact.node_xi;
    let measure = |e: usize, x: f64| measure(contact, model, e, x);
    let q = mult.n_dofs();
    let mut gap_moments = vec![0.0; q];
    // Where the obstacle turns, its surface's motion along each edge varies: ∫ψ_j s(ξ).
    let mut shift_moments = if obstacle.rotation.is_some() { vec![0.0; q] } else { Vec::new() };
    for pc in &common_refinement(fe, &mult.xi) {
        let (half, mid) = (0.5 * (pc.b - pc.a), 0.5 * (pc.a + pc.b));
        for &(t, w) in &GAUSS4 {
            let x = mid + half * t;
            let g = obstacle.gap(contact, x)?;
            let s = if shift_moments.is_empty() {
                0.0
            } else {
                obstacle.tangential_motion(
                    contact.surface_point(x),
                    contact.frame_at(x).1,
                    contact.edges[pc.edge].length,
                )
            };
            let (psi, npsi) = mult.basis(pc.cell, x);
            for &(i, pi) in &psi[..npsi] {
                gap_moments[i] += w * half * measure(pc.edge, x) * pi * g;
                if let Some(m) = shift_moments.get_mut(i) {
                    *m += w * half * measure(pc.edge, x) * pi * s;
                }
            }
        }
    }
    Ok((gap_moments, shift_moments))
}

/// The measure at abscissa x of edge e of Γ_C: 1, or `2π r(x)` in axisymmetry.
fn measure(contact: &ContactBoundary, model: Model, e: usize, x: f64) -> f64 {
    if !model.is_axisymmetric() {
        return 1.0;
    }
    let fe = &contact.node_xi;
    let s = (x - fe[e]) / (fe[e + 1] - fe[e]);
    let (a, b) = (contact.node_points[e], contact.node_points[e + 1]);
    radial_weight((1.0 - s) * a[0] + s * b[0])
}
