//! Typed errors: bad input is an [`enum@Error`], never a panic.
//!
//! Numerical outcomes of a solve (converged, iteration cap reached, QP failed) are *not* errors: they are
//! reported by [`crate::SolveStatus`] inside the solution, so a caller always sees how far a solve got.

use thiserror::Error;

mod details;
mod num;

pub use details::{Detail, ErrorCategory};
pub use num::Num;

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
        "triangle {element} is degenerate: area {} is negligible next to its squared diameter {}",
        Num(*.area),
        Num(*.diameter_sq)
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
        "triangle {element} is inverted (clockwise node order, signed area {}); list its nodes counter-clockwise",
        Num(*.area)
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
    /// Coordinates so large that a triangle's area or diameter overflows.
    #[error("triangle {element}: its coordinates are too large for its area ({}) and diameter² ({}) to be computed; rescale the mesh", Num(*.area), Num(*.diameter_sq))]
    CoordinatesTooLarge {
        /// Triangle index.
        element: usize,
        /// The area computed.
        area: f64,
        /// The squared diameter computed.
        diameter_sq: f64,
    },
    /// Two triangles lie on the same side of an edge (the same directed edge): they overlap, the mesh is
    /// folded.
    #[error("triangles {first} and {second} overlap: both have the edge {a} → {b} on the same side (a folded mesh)")]
    OverlappingTriangles {
        /// First triangle.
        first: usize,
        /// Second triangle.
        second: usize,
        /// Edge start node.
        a: usize,
        /// Edge end node.
        b: usize,
    },
    /// An edge set lists an edge twice (a load on it would count twice).
    #[error("edge set '{set}' lists the edge ({a}, {b}) twice (positions {first} and {second})")]
    DuplicateEdge {
        /// Name of the edge set.
        set: String,
        /// First position.
        first: usize,
        /// Second position.
        second: usize,
        /// First node.
        a: usize,
        /// Second node.
        b: usize,
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
    /// A curve given to an edge set is not valid, or does not pass through the set's nodes.
    #[error("the curve of edge set '{set}': {what}")]
    BadCurve {
        /// Name of the edge set.
        set: String,
        /// What is wrong.
        what: String,
        /// The node off the curve, if that is what is wrong.
        node: Option<usize>,
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
    /// A triangle marked for refinement does not exist.
    #[error("marked triangle {triangle} (position {position} of the marks) does not exist: the mesh has {n_triangles} triangles")]
    MarkedTriangleOutOfRange {
        /// Position in the list of marks.
        position: usize,
        /// The marked index.
        triangle: usize,
        /// Number of triangles of the mesh.
        n_triangles: usize,
    },
    /// A refinement would produce more triangles than the limit of the mesh generators.
    #[error("the refined mesh would have {triangles} triangles, more than the limit of {limit}")]
    RefinementTooLarge {
        /// Triangles the refined mesh would have.
        triangles: usize,
        /// The limit ([`crate::mesh::generate::MAX_CELLS`]).
        limit: usize,
    },
    /// A nodal vector does not have the length its mesh and number of components ask for.
    #[error("a nodal vector of {len} values does not match {n_nodes} nodes with {components} components each")]
    NodalValuesLength {
        /// Length of the vector given.
        len: usize,
        /// Number of nodes.
        n_nodes: usize,
        /// Values per node.
        components: usize,
    },

    /// An axisymmetric body's mesh is not a meridian section (a node at r < 0), or the model is asked of
    /// what it does not take.
    #[error("axisymmetric model: {what}")]
    BadAxisymmetry {
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
    /// A piece of the body (triangles joined through edges) has no support: it can move freely.
    #[error("the piece of {triangles} triangles containing triangle {triangle} (node {node}) has no support (no clamped, roller or displaced node): it can move freely, so the stiffness is singular (the mesh has {pieces} pieces joined through edges; pieces joined at a single node count as separate)")]
    FloatingPiece {
        /// A triangle of the piece.
        triangle: usize,
        /// A node of the piece.
        node: usize,
        /// Number of triangles in the piece.
        triangles: usize,
        /// Number of pieces of the mesh.
        pieces: usize,
    },
    /// A piece of the body is supported, but its supports leave a rigid motion free (rollers all
    /// parallel, a single held node).
    #[error("the supports of the piece of {triangles} triangles containing triangle {triangle} (held at node {node}, among others) leave a rigid motion free: {motion}; the stiffness is singular (the mesh has {pieces} pieces joined through edges; pieces joined at a single node count as separate)")]
    RigidMotion {
        /// A triangle of the piece.
        triangle: usize,
        /// A held node of the piece.
        node: usize,
        /// Number of triangles in the piece.
        triangles: usize,
        /// Number of pieces of the mesh.
        pieces: usize,
        /// The free motion in words (a translation along a direction, or a rotation about a point).
        motion: String,
    },
    /// A roller on an edge set that is not straight (its normal would not be defined).
    #[error("roller on '{set}': the set is not straight, node {node} lies {distance:e} off the line of its first edge (edge length {length:e}); a roller needs one normal")]
    SupportNotStraight {
        /// Edge set name.
        set: String,
        /// Offending node.
        node: usize,
        /// Its distance to the line.
        distance: f64,
        /// Local edge length it is compared with.
        length: f64,
    },
    /// Two supports impose conditions on one node that cannot both hold.
    #[error("the supports on '{first}' and '{second}' conflict at node {node}: {what}")]
    ConflictingSupports {
        /// The node.
        node: usize,
        /// The set of the first condition at the node.
        first: String,
        /// The set of the condition that disagrees.
        second: String,
        /// The two conditions.
        what: String,
    },
    /// Two supports fix a node by conditions so nearly parallel that they turn their data into a
    /// displacement beyond small displacements: larger than the body and than any pair of orthogonal
    /// conditions on the same data could give (see [`crate::fem::supports`]).
    #[error(
        "the supports on '{first}' and '{second}' meet at node {node} at an angle of {angle_degrees:.3e}°: \
         they move it by {displacement:e} from data of at most {data:e}, beyond the body's size {size:e} \
         (nearly parallel conditions amplify their data by 1/sin θ; make them parallel or their data agree)"
    )]
    NearlyParallelSupports {
        /// The node.
        node: usize,
        /// The set of the first condition.
        first: String,
        /// The set of the second condition.
        second: String,
        /// The angle between the two conditions' directions, in degrees.
        angle_degrees: f64,
        /// The length of the displacement they prescribe.
        displacement: f64,
        /// The largest prescribed value at the node.
        data: f64,
        /// The body's size (the diagonal of the mesh's bounding box).
        size: f64,
    },
    /// A support's data are unusable (a non-finite value, a displacement with no component).
    #[error("support on '{set}': {what}")]
    BadSupport {
        /// Edge set name.
        set: String,
        /// What is wrong.
        what: String,
    },
    /// Every node of Γ_C is fixed by the supports: no multiplier can act.
    #[error(
        "every node of the contact boundary '{set}' is fixed by the supports: the contact conditions cannot act on it"
    )]
    ContactFullyClamped {
        /// Edge set name.
        set: String,
    },
    /// The supports prescribe a node of Γ_C into the obstacle: no solution can satisfy the contact condition.
    #[error("the supports prescribe node {node} of the contact boundary into the obstacle{}: its normal displacement is {} against the gap {}, {} beyond it; the contact condition cannot hold there (free that node's normal displacement, or move the obstacle)", .step.map_or(String::new(), |k| format!(" at step {k}")), Num(*.u_n), Num(*.gap), Num(*.u_n - *.gap))]
    PrescribedPenetration {
        /// The node (a node of Γ_C whose normal displacement a support prescribes).
        node: usize,
        /// Its prescribed normal displacement `u · n`.
        u_n: f64,
        /// The gap `g₀ − δ` there.
        gap: f64,
        /// The step of a history (0-based), or `None` for a static solve.
        step: Option<usize>,
    },
    /// The solve's equilibrium residual shows a singular or nearly singular stiffness.
    #[error("the stiffness is singular or nearly so: the equilibrium residual of the solution is {} (more than √ε); look for a mechanism or a material at its limits", Num(*.residual))]
    SingularStiffness {
        /// The relative equilibrium residual.
        residual: f64,
    },
    /// No support: the elastic problem would be singular.
    #[error(
        "no support: the body must be held on a part of its boundary (Γ_D: clamped, roller or displacement edge sets)"
    )]
    NoDirichlet,

    // ----- contact geometry -----
    /// Γ_C is not one chain of edges (open, or a closed loop): several pieces, a branch, or edges that overlap.
    #[error("contact boundary '{set}' is not one chain of edges: {what}")]
    ContactNotConnected {
        /// Edge set name.
        set: String,
        /// What is wrong.
        what: String,
    },
    /// An edge of Γ_C also carries a support (Γ_C and Γ_D must not overlap).
    #[error("contact boundary '{set}' overlaps the supported boundary (Γ_D) on edge ({a}, {b})")]
    ContactOverlapsDirichlet {
        /// Edge set name.
        set: String,
        /// First node.
        a: usize,
        /// Second node.
        b: usize,
    },
    /// The two sides of a contact pair do not form one: bodies or edge sets that do not exist, contact
    /// lines that are not one line with opposite normals, a primary line that does not cover the secondary
    /// one, an obstacle motion on a pair, or a capability not yet available for two bodies.
    #[error("contact pair (secondary '{secondary}', primary '{primary}'): {what}")]
    ContactPair {
        /// The secondary side (`body.edge_set`).
        secondary: String,
        /// The primary side (`body.edge_set`).
        primary: String,
        /// What is wrong.
        what: String,
    },
    /// Several contact pairs in one problem that do not fit together (sides sharing an edge, an edge set twice), an
    /// edge of a further pair on the primary side of two bodies, or a pair's own μ under a law other than Coulomb.
    #[error("contact pair '{pair}': {what}")]
    SeveralPairs {
        /// The pair (its contact edge set).
        pair: String,
        /// What is wrong.
        what: String,
    },
    /// A body held only by the contact (its supports leave it a free rigid motion) that the contact cannot
    /// hold: free to slide along a frictionless contact, or two bodies free to move together.
    #[error("body '{body}' is held only by the contact, which leaves it free: {motion}; {what}: hold that motion with a support")]
    HeldOnlyByContact {
        /// The body (`"body"` for one body).
        body: String,
        /// The free motion in words.
        motion: String,
        /// Why the contact cannot hold it.
        what: String,
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
    #[error("multiplier point {index} lies off the contact boundary: distance {} (Γ_C spans abscissae [{}, {}])", Num(*.distance), Num(*.start), Num(*.end))]
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
    /// The multiplier mesh cannot be built: fewer than two points, a non-finite point, or a size or
    /// ratio that is not positive and finite.
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
    #[error("γ0 = {:.4} is not admissible: K − G stays positive definite only for γ0 < {:.4} (bound set by element {element}); choose γ0 as a fraction of the bound", Num(*.gamma0), Num(*.bound))]
    Gamma0TooLarge {
        /// The requested γ0.
        gamma0: f64,
        /// The admissible bound.
        bound: f64,
        /// The element that sets the bound.
        element: usize,
    },
    /// A setting name that does not exist.
    #[error("setting '{name}' is not known (known settings: {known})")]
    UnknownSetting {
        /// The name given.
        name: String,
        /// The known names, comma separated.
        known: String,
    },
    /// A setting was given a value of the wrong kind (a number for a choice, a fraction for a count…).
    #[error("setting '{name}': {what}")]
    BadSettingValue {
        /// Name of the setting.
        name: &'static str,
        /// What is wrong.
        what: String,
    },
    /// A step of a loading history is not valid.
    #[error("load step {step}: {what}")]
    BadLoadStep {
        /// The step (0-based).
        step: usize,
        /// What is wrong.
        what: String,
    },
    /// A name that is not one of the options of a choice.
    #[error("{what} '{got}' is not known (options: {options})")]
    UnknownChoice {
        /// What the name chooses (`"multiplier space"`).
        what: &'static str,
        /// The name given.
        got: String,
        /// The options, comma separated.
        options: String,
    },
    /// A friction law given by keywords that contradict each other or miss a value.
    #[error("friction: {what}")]
    BadFriction {
        /// What is wrong.
        what: String,
    },
    /// A Tresca threshold vector has the wrong length or bad values.
    #[error("Tresca threshold: {what}")]
    BadThreshold {
        /// What is wrong.
        what: String,
    },

    // ----- linear algebra -----
    /// A sparse matrix could not be assembled (index overflow or allocation failure in faer).
    #[error("assembly of {matrix} failed: {what}")]
    Assembly {
        /// Which matrix.
        matrix: &'static str,
        /// Details from faer.
        what: String,
    },
    /// The (stabilized) stiffness matrix could not be factorized.
    #[error("the stiffness matrix A = K − G is not positive definite (Cholesky failed): {what}")]
    NotPositiveDefinite {
        /// Details from the factorization.
        what: String,
    },
    /// A solve would need more memory for its dense parts than the budget allows.
    #[error("{what} would need {} bytes, more than the memory budget of {} bytes (setting 'memory_budget')", Num(*.needed), Num(*.budget))]
    MemoryBudget {
        /// What would be allocated.
        what: String,
        /// Bytes it would need.
        needed: f64,
        /// The budget in bytes.
        budget: f64,
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

/// The message for a subnormal datum (a length or displacement below `f64::MIN_POSITIVE` ≈ 2.2e-308, but
/// not 0): such a number keeps only a few of its digits, and the answer of a linear problem, which scales
/// with it, would keep as few; normal numbers down to 2.2e-308 are solved as accurately as any other.
pub(crate) fn subnormal(name: &str, value: f64) -> String {
    format!(
        "{name} = {value:e} is subnormal (below {:e}): it keeps only a few digits; choose units in which it is a \
         normal number",
        f64::MIN_POSITIVE
    )
}
