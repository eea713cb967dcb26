//! Typed errors: bad input is an [`enum@Error`], never a panic.
//!
//! Numerical outcomes of a solve (converged, iteration cap reached, QP failed) are *not* errors: they are
//! reported by [`crate::SolveStatus`] inside the solution, so a caller always sees how far a solve got.

use thiserror::Error;

/// Everything that can be wrong with the input of a tribo problem.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    // ----- mesh -----
    /// A coordinate is NaN or infinite.
    #[error("node {node} has a non-finite coordinate ({x}, {y})")]
    NonFiniteCoordinate {
        /// Node index.
        node: usize,
        /// x coordinate.
        x: f64,
        /// y coordinate.
        y: f64,
    },
    /// A triangle refers to a node that does not exist.
    #[error("triangle {element} refers to node {node}, but the mesh has {n_nodes} nodes")]
    NodeIndexOutOfRange {
        /// Triangle index.
        element: usize,
        /// The offending node index.
        node: usize,
        /// Number of nodes.
        n_nodes: usize,
    },
    /// A triangle has zero (or, relative to its size, negligible) area.
    #[error(
        "triangle {element} is degenerate: area {area:e} is negligible next to its squared diameter {diameter_sq:e}"
    )]
    DegenerateTriangle {
        /// Triangle index.
        element: usize,
        /// Signed area.
        area: f64,
        /// Squared diameter, the scale the area is compared with.
        diameter_sq: f64,
    },
    /// A triangle is ordered clockwise.
    #[error(
        "triangle {element} is inverted (clockwise node order, signed area {area:e}); list its nodes counter-clockwise"
    )]
    InvertedTriangle {
        /// Triangle index.
        element: usize,
        /// Signed area (negative).
        area: f64,
    },
    /// A node belongs to no triangle.
    #[error("node {node} belongs to no triangle")]
    UnusedNode {
        /// Node index.
        node: usize,
    },
    /// Two triangles have the same three nodes.
    #[error("triangles {first} and {second} have the same nodes")]
    DuplicateTriangle {
        /// First triangle.
        first: usize,
        /// Second triangle.
        second: usize,
    },
    /// An edge of an edge set is not an edge on the boundary of the mesh.
    #[error("edge {index} ({a}, {b}) of edge set '{set}' is not a boundary edge of the mesh")]
    NotABoundaryEdge {
        /// Name of the edge set.
        set: String,
        /// Position of the edge in the set.
        index: usize,
        /// First node.
        a: usize,
        /// Second node.
        b: usize,
    },
    /// An edge set name was asked for that the mesh does not have.
    #[error("the mesh has no edge set named '{name}' (it has: {available})")]
    UnknownEdgeSet {
        /// The name asked for.
        name: String,
        /// The names the mesh has, comma separated.
        available: String,
    },
    /// An edge set is empty.
    #[error("edge set '{name}' is empty")]
    EmptyEdgeSet {
        /// The name of the set.
        name: String,
    },
    /// A mesh has no triangle.
    #[error("the mesh has no triangle")]
    EmptyMesh,
    /// A mesh generator was given bad parameters.
    #[error("mesh generator: {what}")]
    BadGenerator {
        /// What is wrong.
        what: String,
    },

    // ----- material, loads, supports -----
    /// A material constant is out of range.
    #[error("material: {what}")]
    BadMaterial {
        /// What is wrong.
        what: String,
    },
    /// A load is not finite.
    #[error("load on '{target}' is not finite: ({x}, {y})")]
    NonFiniteLoad {
        /// Edge set name, or "body" for the body force.
        target: String,
        /// x component.
        x: f64,
        /// y component.
        y: f64,
    },
    /// No clamped edge: the elastic problem would be singular.
    #[error("no clamped edge set: the body must be clamped on a part of its boundary (Γ_D) of positive length")]
    NoDirichlet,

    // ----- contact geometry -----
    /// Γ_C is not one straight segment.
    #[error("contact boundary '{set}' is not straight: node {node} lies {distance:e} off the line of the first edge (edge length {length:e})")]
    ContactNotStraight {
        /// Edge set name.
        set: String,
        /// Offending node.
        node: usize,
        /// Its distance to the line.
        distance: f64,
        /// Local edge length it is compared with.
        length: f64,
    },
    /// Γ_C is made of several pieces, or edges overlap.
    #[error("contact boundary '{set}' is not one connected segment: {what}")]
    ContactNotConnected {
        /// Edge set name.
        set: String,
        /// What is wrong.
        what: String,
    },
    /// Γ_C is entirely clamped.
    #[error("contact boundary '{set}' overlaps the clamped boundary on edge ({a}, {b})")]
    ContactOverlapsDirichlet {
        /// Edge set name.
        set: String,
        /// First node.
        a: usize,
        /// Second node.
        b: usize,
    },
    /// A traction is applied on Γ_C: the method takes σ(u)·n = −λ there, so Γ_N and Γ_C must not overlap.
    #[error("traction set '{traction_set}' shares edge ({a}, {b}) with the contact boundary '{set}': Γ_N and Γ_C must not overlap")]
    TractionOnContact {
        /// Contact edge set name.
        set: String,
        /// Traction edge set name.
        traction_set: String,
        /// First node.
        a: usize,
        /// Second node.
        b: usize,
    },
    /// An obstacle description is bad.
    #[error("obstacle: {what}")]
    BadObstacle {
        /// What is wrong.
        what: String,
    },

    // ----- multipliers -----
    /// Multiplier points are not strictly increasing.
    #[error("multiplier points must be strictly increasing: point {index} (abscissa {value}) does not exceed the previous one ({previous})")]
    MultiplierPointsNotIncreasing {
        /// Index of the offending point.
        index: usize,
        /// Its abscissa.
        value: f64,
        /// The previous abscissa.
        previous: f64,
    },
    /// A multiplier point lies off Γ_C.
    #[error("multiplier point {index} lies off the contact boundary: distance {distance:e} (Γ_C spans abscissae [{start}, {end}])")]
    MultiplierPointOffContact {
        /// Index of the point.
        index: usize,
        /// Distance to Γ_C (to the line for 2D points, along the line for abscissae beyond the ends).
        distance: f64,
        /// Abscissa of the start of Γ_C.
        start: f64,
        /// Abscissa of the end of Γ_C.
        end: f64,
    },
    /// The multiplier points do not reach an end of Γ_C.
    #[error(
        "the multiplier mesh must cover Γ_C: its {which} point is at abscissa {value}, Γ_C {which}s at {expected}"
    )]
    MultiplierMeshDoesNotCover {
        /// "first" or "last".
        which: &'static str,
        /// Abscissa of that point.
        value: f64,
        /// Abscissa of the end of Γ_C.
        expected: f64,
    },
    /// A multiplier mesh size is not positive.
    #[error("multiplier mesh: {what}")]
    BadMultiplierMesh {
        /// What is wrong.
        what: String,
    },

    // ----- settings -----
    /// A setting is out of range.
    #[error("setting '{name}' = {value}: {what}")]
    BadSetting {
        /// Name of the setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What range it must be in.
        what: String,
    },
    /// γ0 is above the bound that keeps the stabilized stiffness positive definite.
    #[error("γ0 = {gamma0:e} is not admissible: K − G stays positive definite only for γ0 < {bound:e} (bound set by element {element}); choose γ0 as a fraction of the bound")]
    Gamma0TooLarge {
        /// The requested γ0.
        gamma0: f64,
        /// The admissible bound.
        bound: f64,
        /// The element that sets the bound.
        element: usize,
    },
    /// A Tresca threshold vector has the wrong length or bad values.
    #[error("Tresca threshold: {what}")]
    BadThreshold {
        /// What is wrong.
        what: String,
    },

    // ----- linear algebra -----
    /// The (stabilized) stiffness matrix could not be factorized.
    #[error("the stabilized stiffness matrix K − G is not positive definite (Cholesky failed): {what}")]
    NotPositiveDefinite {
        /// Details from the factorization.
        what: String,
    },
    /// The QP solver refused the problem at setup.
    #[error("the QP solver could not be set up: {what}")]
    QpSetup {
        /// The message of the solver.
        what: String,
    },
}

/// Shorthand for results of tribo.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Rejects a non-finite or out-of-range scalar setting.
pub(crate) fn check_setting(name: &'static str, value: f64, ok: bool, what: &str) -> Result<()> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(Error::BadSetting { name, value, what: what.to_string() })
    }
}
