//! A wedge forced into a rigid V-groove (issue 40, `tests/integration/coulomb_newton.rs` and study 20): the
//! problem where the Coulomb fixed point fails.
//!
//! The wedge is the triangle with its tip at the origin and its top, of half-width `H tan α`, at y = H = 1: its
//! two flanks (the edge set `flanks`, one bent Γ_C through the tip) sit in a rigid groove of the same angle,
//! given by its signed distance (the smaller of the distances to the two flank lines). A traction (0, −q) on its
//! top (`top`) pushes it in; nothing else holds it (force control, the contact holds its three rigid motions).
//! E = 1, P1 multipliers on the FE edges.
//!
//! Sliding in, each flank carries λ_n and the friction μ λ_n up along it: the load balances
//! `2 (λ_n sin α + μ λ_n cos α)` per unit length. The fixed point freezes the friction bound at the previous
//! λ_n, so it solves `λ_n^{k+1} sin α = q' − μ λ_n^k cos α`: its error is multiplied by `−μ cot α` per iteration,
//! and beyond μ = tan α (as long as the flanks slip) it oscillates instead of converging. Above a larger μ the
//! wedge sticks (it wedges itself in) and the bound no longer drives the iteration.

use std::sync::Arc;

use tribo::*;

/// The wedge of half-angle `alpha_deg` (degrees) and height 1 on a structured mesh of `n` rows of triangles.
///
/// # Panics
/// If `n` is 0 or the angle is not in (0°, 90°) (a test's own parameters).
pub fn wedge_mesh(n: usize, alpha_deg: f64) -> Mesh {
    assert!(n > 0 && alpha_deg > 0.0 && alpha_deg < 90.0, "a wedge needs rows and an angle in (0°, 90°)");
    let width = alpha_deg.to_radians().tan();
    let id = |i: usize, j: usize| j * (j + 1) / 2 + i;
    let mut points = Vec::new();
    for j in 0..=n {
        let y = j as f64 / n as f64;
        points.extend((0..=j).map(|i| [width * (2.0 * i as f64 - j as f64) / n as f64, y]));
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..=j {
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            if i < j {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            }
        }
    }
    let flanks = (0..n).flat_map(|j| [[id(0, j + 1), id(0, j)], [id(j, j), id(j + 1, j + 1)]]).collect();
    let top = (0..n).map(|i| [id(i + 1, n), id(i, n)]).collect();
    let sets = [("flanks".to_string(), flanks), ("top".to_string(), top)].into();
    // Valid by construction: counterclockwise triangles, the flanks and the top on the boundary.
    Mesh::new(points, triangles, sets).expect("a structured wedge is a valid mesh")
}

/// The rigid V-groove that fits the wedge of half-angle `alpha_deg`: the signed distance `min(n_L · x, n_R · x)`,
/// n_L and n_R the unit normals of its two flank lines through the origin, toward the wedge.
pub fn groove(alpha_deg: f64) -> ObstacleShape {
    let (sin, cos) = alpha_deg.to_radians().sin_cos();
    let (left, right) = ([cos, sin], [-cos, sin]);
    ObstacleShape::Distance(DistanceFunction(Arc::new(move |p: [f64; 2]| {
        (left[0] * p[0] + left[1] * p[1]).min(right[0] * p[0] + right[1] * p[1])
    })))
}

/// The same groove as a [`ObstacleShape::Profile`]: the polyline from the top of its left flank down to the tip and
/// up its right flank (the groove on its right), its ends extended.
pub fn groove_profile(alpha_deg: f64) -> ObstacleShape {
    let (sin, cos) = alpha_deg.to_radians().sin_cos();
    ObstacleShape::Profile { points: vec![[-sin, cos], [0.0, 0.0], [sin, cos]] }
}

/// The wedge of [`wedge_mesh`] (n rows, half-angle `alpha_deg`, Poisson's ratio `poisson`, E = 1) pushed into
/// its [`groove`] by the traction (0, −0.001) on its top.
///
/// # Panics
/// As [`wedge_mesh`], and for a Poisson's ratio a material refuses.
pub fn wedge_problem(n: usize, alpha_deg: f64, poisson: f64) -> Problem {
    let spec = ProblemSpec::new(Material { young: 1.0, poisson }, "flanks")
        .traction("top", [0.0, -1e-3])
        .obstacle(groove(alpha_deg));
    // An internal invariant of this dev-only kit (no user input reaches it): a valid wedge mesh, its flanks one
    // chain through the tip, a valid groove and E = 1; only the caller's ν can be refused, a test's own parameter.
    Problem::new(wedge_mesh(n, alpha_deg), spec).expect("the wedge in its groove is a valid problem")
}
