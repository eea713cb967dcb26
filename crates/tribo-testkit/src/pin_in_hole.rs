//! An elastic pin in a hole of an elastic plate with clearance, pushed across (issue 39, conformal contact; the
//! reference is [`crate::Persson`]): the upper half by symmetry.
//!
//! The hole has radius R = 1, the pin 1 − ΔR; both bodies are of one material, in plane strain, frictionless. The
//! pin is a uniform half-disc whose centre cell is cut out: that small core (radius 1 / `rings`) is moved rigidly
//! by (δ, 0), which loads the pin as a force at its centre does as r₀ → 0 (Persson's pin: the mode-1 rim motion
//! goes into the approach; the core stiffens the higher modes a little, below). The plate is a square of half-width `half_width` with the hole at
//! its centre, clamped on its three outer sides. Both lie on rollers along y = 0. The pin's rim is the secondary
//! side (P1 multipliers on its FE edges), the hole's upper half the primary; both carry their circles, and both
//! meshes are bisected `refinements` times in a band along the arc `0 ≤ θ ≤ window`, each time within 8 cells of
//! the circle, so that their cells there are `2^−refinements` of the coarse ones.
//!
//! What the idealization leaves out, from the mode compliances of [`crate::Persson`]'s derivation computed for a
//! disc with a rigid core and for a ring clamped outside (Muskhelishvili's potentials): a core of radius r₀ stiffens
//! the pin's mode 2 by about 4 r₀² (0.25 % at r₀ = 0.025) and its higher modes by far less; a plate clamped at
//! radius c stiffens the hole's mode 2 by about 4.5 / c² (0.07 % at c = 80).

use std::f64::consts::PI;

use tribo::mesh::refine::{bisect, label_longest_edge};
use tribo::*;

use crate::Persson;

/// A pin pushed across a hole with clearance (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct PinInHole {
    /// The clearance ΔR (the hole's radius is 1).
    pub clearance: f64,
    /// The material of both bodies.
    pub material: Material,
    /// The plate's half-width.
    pub half_width: f64,
    /// Rings of the pin's coarse uniform half-disc (its cut-out core has radius 1 / rings).
    pub rings: usize,
    /// Nodes round the whole hole on the plate's coarse mesh (a multiple of 8) and cells across it.
    pub around: [usize; 2],
    /// Bisections along the contact arc.
    pub refinements: usize,
    /// The refined arc, 0 ≤ θ ≤ window.
    pub window: f64,
    /// The core's displacement δ along x.
    pub approach: f64,
    /// Whether the pin's rim is the secondary side (it carries the multipliers), or the hole's.
    pub multipliers_on_pin: bool,
}

impl PinInHole {
    /// ΔR = 10⁻³, E = 1, ν = 0.3, a plate of half-width 80, a coarse pin of 40 rings (core radius 0.025) and plate of
    /// 128 nodes round the hole and 36 cells across, bisected `refinements` times along `0 ≤ θ ≤ window`.
    pub fn new(approach: f64, window: f64, refinements: usize) -> Self {
        Self {
            clearance: 1e-3,
            material: Material { young: 1.0, poisson: 0.3 },
            half_width: 80.0,
            rings: 40,
            around: [128, 36],
            refinements,
            window,
            approach,
            multipliers_on_pin: true,
        }
    }

    /// The composite modulus E* = E / (2 (1 − ν²)) of the two bodies.
    pub fn composite_modulus(&self) -> f64 {
        self.material.young / (2.0 * (1.0 - self.material.poisson.powi(2)))
    }

    /// The two-body problem: bodies `"pin"` and `"plate"`, the pair `"pin.rim"` on `"plate.hole"`.
    ///
    /// # Panics
    /// For sizes the generators or the pair refuse (test support: no user input reaches this fixture; the tests and
    /// the study pass sizes that make a valid scene, and a broken fixture stops with the generator's message). The
    /// meshes' own steps (the core cut out, the half plate, the curves on their arcs, the bisections) keep a valid
    /// mesh of a valid one, and panic only if that invariant breaks.
    pub fn problem(&self) -> Problem {
        let (pin_mesh, plate_mesh) =
            (self.refined(self.pin_mesh(), 1.0 - self.clearance), self.refined(self.plate_mesh(), 1.0));
        let pin = Body {
            name: "pin".into(),
            materials: Materials::uniform(self.material, pin_mesh.n_triangles()),
            mesh: pin_mesh,
            clamped: vec![],
            supports: vec![
                Support::displacement("core", Some(self.approach), Some(0.0)),
                Support::roller("start"),
                Support::roller("end"),
            ],
            tractions: vec![],
        };
        let plate = Body {
            name: "plate".into(),
            materials: Materials::uniform(self.material, plate_mesh.n_triangles()),
            mesh: plate_mesh,
            clamped: vec!["right".into(), "top".into(), "left".into()],
            supports: vec![Support::roller("symmetry")],
            tractions: vec![],
        };
        let (mut secondary, mut primary) = ("pin.rim", "plate.hole");
        if !self.multipliers_on_pin {
            (secondary, primary) = (primary, secondary);
        }
        // the shrink fit's pair: P1 multipliers on the secondary's FE edges, touching, plane strain
        let pair = ContactPair { secondary: secondary.into(), primary: primary.into(), ..crate::ring_pair() };
        // The fixture's own sizes make a valid pair; a broken fixture panics with the message.
        Problem::two_bodies([pin, plate], pair, [0.0, 0.0]).expect("a valid pin in a hole")
    }

    /// The pin: a uniform half-disc less the triangles at its centre; edge sets `rim`, `start`, `end` and `core`.
    fn pin_mesh(&self) -> Mesh {
        let sector = DiscSector { center: [0.0, 0.0], radius: 1.0 - self.clearance, angles: [0.0, PI] };
        let disc = disc(&sector, self.rings).expect("the fixture's own disc");
        let centre = 0; // the generator's first node
        let kept: Vec<[usize; 3]> = disc.triangles().iter().filter(|t| !t.contains(&centre)).copied().collect();
        // (the edge of each centre triangle opposite the centre, counterclockwise)
        let core: Vec<[usize; 2]> = disc
            .triangles()
            .iter()
            .filter_map(|t| t.iter().position(|&v| v == centre).map(|i| [t[(i + 1) % 3], t[(i + 2) % 3]]))
            .collect();
        let mut sets = disc.edge_sets().clone();
        for side in ["start", "end"] {
            sets.entry(side.into()).and_modify(|edges| edges.retain(|e| !e.contains(&centre)));
        }
        sets.insert("core".into(), core);
        let mesh = compact(disc.points(), &kept, sets);
        mesh.with_curve("rim", Curve::Arc { center: [0.0, 0.0], radius: 1.0 - self.clearance }).expect("the rim's arc")
    }

    /// The plate: the upper half of a square plate with the hole; edge sets `hole`, `right`, `top`, `left` and
    /// `symmetry` (y = 0).
    fn plate_mesh(&self) -> Mesh {
        let plate = PlateWithHole { center: [0.0, 0.0], radius: 1.0, half_widths: [self.half_width; 2] };
        let full = plate_with_hole(&plate, self.around[0], self.around[1]).expect("the fixture's own plate");
        let p = full.points();
        // (the generator puts the nodes at half a turn on y = 0 exactly)
        let on_axis = |v: usize| p[v][1] == 0.0;
        let upper: Vec<[usize; 3]> =
            full.triangles().iter().filter(|t| t.iter().map(|&v| p[v][1]).sum::<f64>() > 0.0).copied().collect();
        let mut sets = full.edge_sets().clone();
        sets.remove("bottom");
        for edges in sets.values_mut() {
            edges.retain(|e| e.iter().all(|&v| p[v][1] >= 0.0));
        }
        // the cut: the boundary edges of the upper half on y = 0
        let directed: std::collections::HashSet<[usize; 2]> =
            upper.iter().flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]]).collect();
        let symmetry = directed
            .iter()
            .filter(|e| !directed.contains(&[e[1], e[0]]) && on_axis(e[0]) && on_axis(e[1]))
            .copied()
            .collect();
        sets.insert("symmetry".into(), symmetry);
        let mesh = compact(p, &upper, sets);
        mesh.with_curve("hole", Curve::Arc { center: [0.0, 0.0], radius: 1.0 }).expect("the hole's arc")
    }

    /// `mesh` bisected along the arc of radius `radius` (module documentation).
    fn refined(&self, mesh: Mesh, radius: f64) -> Mesh {
        let mut mesh = label_longest_edge(&mesh);
        for _ in 0..self.refinements {
            let p = mesh.points();
            let near: Vec<usize> = (0..mesh.n_triangles())
                .filter(|&t| {
                    let [a, b, c] = mesh.triangles()[t].map(|v| p[v]);
                    let centroid = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
                    let h = mesh.diameter(t);
                    let from_arc = ((centroid[0].hypot(centroid[1]) - radius).abs() - 8.0 * h).max(0.0);
                    centroid[1].atan2(centroid[0]) <= self.window + 4.0 * h && from_arc == 0.0
                })
                .collect();
            mesh = bisect(&mesh, &near, Bisection::AllEdges).expect("the fixture's refinement").into_mesh();
        }
        mesh
    }

    /// Persson's solution at the load this problem's answer carries (derived in [`crate::Persson`]'s module),
    /// with that load P = 2 |F_x| (both halves).
    pub fn reference(&self, solution: &Solution) -> Persson {
        let load = 2.0 * solution.contact_force[0].abs();
        Persson::at_load(load / (self.composite_modulus() * self.clearance))
    }

    /// The answer's contact half-angle: the width of its contact zone along the pin's rim (from θ = 0, where the
    /// zone meets the symmetry line), over the rim's radius.
    pub fn half_angle(&self, solution: &Solution) -> f64 {
        solution.contact_width() / if self.multipliers_on_pin { 1.0 - self.clearance } else { 1.0 }
    }

    /// The unit of Persson's pressure for λ_n: `E* ΔR / r`, r the radius of the side that carries the multipliers
    /// (1 − ΔR for the pin's rim, 1 for the hole). The linear theory puts both rims at R = 1; the force per radian
    /// `λ_n r` is what the two sides share, and it is compared (the pin's λ_n is 1 / (1 − ΔR) times the hole's).
    pub fn pressure_unit(&self) -> f64 {
        let r = if self.multipliers_on_pin { 1.0 - self.clearance } else { 1.0 };
        self.composite_modulus() * self.clearance / r
    }

    /// The relative L2(Γ_C) difference of λ_n from Persson's pressure `p̂(θ)` in [`PinInHole::pressure_unit`]s
    /// (exactly on T_H's cells by 4-point Gauss, θ the angle of each point of the rim).
    pub fn pressure_error(&self, problem: &Problem, solution: &Solution, reference: &Persson) -> f64 {
        let scale = self.pressure_unit();
        let mult = &problem.multipliers;
        let gauss =
            [(-0.861_136_311_594_052_6, 0.347_854_845_137_453_9), (-0.339_981_043_584_856, 0.652_145_154_862_546_1)];
        let points = gauss.iter().flat_map(|&(x, w)| [(x, w), (-x, w)]);
        let (mut err, mut norm) = (0.0, 0.0);
        for cell in 0..mult.xi.len() - 1 {
            let (x0, x1) = (mult.xi[cell], mult.xi[cell + 1]);
            for (g, w) in points.clone() {
                let x = 0.5 * (x0 + x1) + 0.5 * (x1 - x0) * g;
                let (b, nb) = mult.basis(cell, x);
                let l: f64 = b[..nb].iter().map(|&(j, v)| v * solution.lambda_n[j]).sum();
                let q = problem.contact.point_at(x);
                let p = scale * reference.pressure(q[1].atan2(q[0]));
                err += 0.5 * (x1 - x0) * w * (l - p).powi(2);
                norm += 0.5 * (x1 - x0) * w * p * p;
            }
        }
        (err / norm).sqrt()
    }
}

/// A mesh of `triangles` (indices into `points`) without the points they do not use, its edge sets renumbered.
fn compact(
    points: &[[f64; 2]],
    triangles: &[[usize; 3]],
    sets: std::collections::BTreeMap<String, Vec<[usize; 2]>>,
) -> Mesh {
    let mut index = vec![usize::MAX; points.len()];
    let mut kept = Vec::new();
    for &v in triangles.iter().flatten() {
        if index[v] == usize::MAX {
            index[v] = kept.len();
            kept.push(points[v]);
        }
    }
    let triangles = triangles.iter().map(|t| t.map(|v| index[v])).collect();
    let sets = sets
        .into_iter()
        .filter(|(_, e)| !e.is_empty())
        .map(|(k, e)| (k, e.iter().map(|e| e.map(|v| index[v])).collect()))
        .collect();
    Mesh::new(kept, triangles, sets).expect("a part of a valid mesh")
}
