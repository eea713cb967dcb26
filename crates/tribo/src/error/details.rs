//! Errors as data: the category of each variant (one Python exception class per category), its name and
//! its fields by name, for structured reports.

use super::Error;

/// What an error is about; the Python binding raises one exception class per category.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorCategory {
    /// The mesh: arrays, coordinates, triangles, edge sets, generator parameters, refinement marks.
    Mesh,
    /// The contact set-up: Γ_C, the obstacle, the multiplier points and space.
    ContactGeometry,
    /// Material, loads, supports, friction law and solver settings (γ0 among them).
    Settings,
    /// The linear algebra refused the problem (assembly, factorization, QP set-up).
    Solver,
}

/// A field of an error, for structured reports ([`Error::details`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Detail {
    /// An index or a count.
    Int(usize),
    /// A value.
    Float(f64),
    /// A name or a message.
    Text(String),
}

impl Error {
    /// What the error is about.
    pub fn category(&self) -> ErrorCategory {
        self.describe().0
    }

    /// The name of the variant (`"DegenerateTriangle"`).
    pub fn kind(&self) -> &'static str {
        self.describe().1
    }

    /// The variant's fields by name (`[("element", Int(3)), ("area", Float(0.0)), …]`).
    pub fn details(&self) -> Vec<(&'static str, Detail)> {
        self.describe().2
    }

    fn describe(&self) -> (ErrorCategory, &'static str, Vec<(&'static str, Detail)>) {
        use Detail::{Float as F, Int as I, Text as T};
        match self {
            Self::NonFiniteCoordinate { node, x, y } => {
                (ErrorCategory::Mesh, "NonFiniteCoordinate", vec![("node", I(*node)), ("x", F(*x)), ("y", F(*y))])
            }
            Self::NodeIndexOutOfRange { element, node, n_nodes } => (
                ErrorCategory::Mesh,
                "NodeIndexOutOfRange",
                vec![("element", I(*element)), ("node", I(*node)), ("n_nodes", I(*n_nodes))],
            ),
            Self::DegenerateTriangle { element, area, diameter_sq } => (
                ErrorCategory::Mesh,
                "DegenerateTriangle",
                vec![("element", I(*element)), ("area", F(*area)), ("diameter_sq", F(*diameter_sq))],
            ),
            Self::InvertedTriangle { element, area } => {
                (ErrorCategory::Mesh, "InvertedTriangle", vec![("element", I(*element)), ("area", F(*area))])
            }
            Self::UnusedNode { node } => (ErrorCategory::Mesh, "UnusedNode", vec![("node", I(*node))]),
            Self::DuplicateTriangle { first, second } => {
                (ErrorCategory::Mesh, "DuplicateTriangle", vec![("first", I(*first)), ("second", I(*second))])
            }
            Self::NotABoundaryEdge { set, index, a, b } => (
                ErrorCategory::Mesh,
                "NotABoundaryEdge",
                vec![("set", T(set.clone())), ("index", I(*index)), ("a", I(*a)), ("b", I(*b))],
            ),
            Self::UnknownEdgeSet { name, available } => (
                ErrorCategory::Mesh,
                "UnknownEdgeSet",
                vec![("name", T(name.clone())), ("available", T(available.clone()))],
            ),
            Self::BadCurve { set, what, node } => (
                ErrorCategory::Mesh,
                "BadCurve",
                [("set", T(set.clone())), ("what", T(what.clone()))]
                    .into_iter()
                    .chain(node.map(|n| ("node", I(n))))
                    .collect(),
            ),
            Self::EmptyEdgeSet { name } => (ErrorCategory::Mesh, "EmptyEdgeSet", vec![("name", T(name.clone()))]),
            Self::EmptyMesh => (ErrorCategory::Mesh, "EmptyMesh", vec![]),
            Self::BadGenerator { what } => (ErrorCategory::Mesh, "BadGenerator", vec![("what", T(what.clone()))]),
            Self::MarkedTriangleOutOfRange { position, triangle, n_triangles } => (
                ErrorCategory::Mesh,
                "MarkedTriangleOutOfRange",
                vec![("position", I(*position)), ("triangle", I(*triangle)), ("n_triangles", I(*n_triangles))],
            ),
            Self::RefinementTooLarge { triangles, limit } => {
                (ErrorCategory::Mesh, "RefinementTooLarge", vec![("triangles", I(*triangles)), ("limit", I(*limit))])
            }
            Self::NodalValuesLength { len, n_nodes, components } => (
                ErrorCategory::Mesh,
                "NodalValuesLength",
                vec![("len", I(*len)), ("n_nodes", I(*n_nodes)), ("components", I(*components))],
            ),
            Self::BadAxisymmetry { what } => (ErrorCategory::Mesh, "BadAxisymmetry", vec![("what", T(what.clone()))]),
            Self::BadMaterial { what } => (ErrorCategory::Settings, "BadMaterial", vec![("what", T(what.clone()))]),
            Self::NonFiniteLoad { target, x, y } => (
                ErrorCategory::Settings,
                "NonFiniteLoad",
                vec![("target", T(target.clone())), ("x", F(*x)), ("y", F(*y))],
            ),
            Self::NoDirichlet => (ErrorCategory::Settings, "NoDirichlet", vec![]),
            Self::TractionOnContact { set, traction_set, a, b } => (
                ErrorCategory::Settings,
                "TractionOnContact",
                vec![("set", T(set.clone())), ("traction_set", T(traction_set.clone())), ("a", I(*a)), ("b", I(*b))],
            ),
            Self::ContactPair { secondary, primary, what } => (
                ErrorCategory::ContactGeometry,
                "ContactPair",
                vec![("secondary", T(secondary.clone())), ("primary", T(primary.clone())), ("what", T(what.clone()))],
            ),
            Self::SeveralPairs { pair, what } => (
                ErrorCategory::ContactGeometry,
                "SeveralPairs",
                vec![("pair", T(pair.clone())), ("what", T(what.clone()))],
            ),
            Self::HeldOnlyByContact { body, motion, what } => (
                ErrorCategory::ContactGeometry,
                "HeldOnlyByContact",
                vec![("body", T(body.clone())), ("motion", T(motion.clone())), ("what", T(what.clone()))],
            ),
            Self::ContactNotConnected { set, what } => (
                ErrorCategory::ContactGeometry,
                "ContactNotConnected",
                vec![("set", T(set.clone())), ("what", T(what.clone()))],
            ),
            Self::ContactOverlapsDirichlet { set, a, b } => (
                ErrorCategory::ContactGeometry,
                "ContactOverlapsDirichlet",
                vec![("set", T(set.clone())), ("a", I(*a)), ("b", I(*b))],
            ),
            Self::BadObstacle { what } => {
                (ErrorCategory::ContactGeometry, "BadObstacle", vec![("what", T(what.clone()))])
            }
            Self::MultiplierPointsNotIncreasing { index, value, previous } => (
                ErrorCategory::ContactGeometry,
                "MultiplierPointsNotIncreasing",
                vec![("index", I(*index)), ("value", F(*value)), ("previous", F(*previous))],
            ),
            Self::MultiplierPointOffContact { index, distance, start, end } => (
                ErrorCategory::ContactGeometry,
                "MultiplierPointOffContact",
                vec![("index", I(*index)), ("distance", F(*distance)), ("start", F(*start)), ("end", F(*end))],
            ),
            Self::MultiplierMeshDoesNotCover { which, value, expected } => (
                ErrorCategory::ContactGeometry,
                "MultiplierMeshDoesNotCover",
                vec![("which", T(which.to_string())), ("value", F(*value)), ("expected", F(*expected))],
            ),
            Self::BadMultiplierMesh { what } => {
                (ErrorCategory::ContactGeometry, "BadMultiplierMesh", vec![("what", T(what.clone()))])
            }
            Self::BadSetting { name, value, what } => (
                ErrorCategory::Settings,
                "BadSetting",
                vec![("name", T(name.to_string())), ("value", F(*value)), ("what", T(what.clone()))],
            ),
            Self::Gamma0TooLarge { gamma0, bound, element } => (
                ErrorCategory::Settings,
                "Gamma0TooLarge",
                vec![("gamma0", F(*gamma0)), ("bound", F(*bound)), ("element", I(*element))],
            ),
            Self::BadThreshold { what } => (ErrorCategory::Settings, "BadThreshold", vec![("what", T(what.clone()))]),
            Self::NotPositiveDefinite { what } => {
                (ErrorCategory::Solver, "NotPositiveDefinite", vec![("what", T(what.clone()))])
            }
            Self::QpSetup { what } => (ErrorCategory::Solver, "QpSetup", vec![("what", T(what.clone()))]),
            Self::CoordinatesTooLarge { element, area, diameter_sq } => (
                ErrorCategory::Mesh,
                "CoordinatesTooLarge",
                vec![("element", I(*element)), ("area", F(*area)), ("diameter_sq", F(*diameter_sq))],
            ),
            Self::OverlappingTriangles { first, second, a, b } => (
                ErrorCategory::Mesh,
                "OverlappingTriangles",
                vec![("first", I(*first)), ("second", I(*second)), ("a", I(*a)), ("b", I(*b))],
            ),
            Self::DuplicateEdge { set, first, second, a, b } => (
                ErrorCategory::Mesh,
                "DuplicateEdge",
                vec![("set", T(set.clone())), ("first", I(*first)), ("second", I(*second)), ("a", I(*a)), ("b", I(*b))],
            ),
            Self::FloatingPiece { triangle, node, triangles, pieces } => (
                ErrorCategory::Settings,
                "FloatingPiece",
                vec![
                    ("triangle", I(*triangle)),
                    ("node", I(*node)),
                    ("triangles", I(*triangles)),
                    ("pieces", I(*pieces)),
                ],
            ),
            Self::RigidMotion { triangle, node, triangles, pieces, motion } => (
                ErrorCategory::Settings,
                "RigidMotion",
                vec![
                    ("triangle", I(*triangle)),
                    ("node", I(*node)),
                    ("triangles", I(*triangles)),
                    ("pieces", I(*pieces)),
                    ("motion", T(motion.clone())),
                ],
            ),
            Self::SupportNotStraight { set, node, distance, length } => (
                ErrorCategory::Settings,
                "SupportNotStraight",
                vec![("set", T(set.clone())), ("node", I(*node)), ("distance", F(*distance)), ("length", F(*length))],
            ),
            Self::ConflictingSupports { node, first, second, what } => (
                ErrorCategory::Settings,
                "ConflictingSupports",
                vec![
                    ("node", I(*node)),
                    ("first", T(first.clone())),
                    ("second", T(second.clone())),
                    ("what", T(what.clone())),
                ],
            ),
            Self::NearlyParallelSupports { node, first, second, angle_degrees, displacement, data, size } => (
                ErrorCategory::Settings,
                "NearlyParallelSupports",
                vec![
                    ("node", I(*node)),
                    ("first", T(first.clone())),
                    ("second", T(second.clone())),
                    ("angle_degrees", F(*angle_degrees)),
                    ("displacement", F(*displacement)),
                    ("data", F(*data)),
                    ("size", F(*size)),
                ],
            ),
            Self::BadSupport { set, what } => {
                (ErrorCategory::Settings, "BadSupport", vec![("set", T(set.clone())), ("what", T(what.clone()))])
            }
            Self::ContactFullyClamped { set } => {
                (ErrorCategory::ContactGeometry, "ContactFullyClamped", vec![("set", T(set.clone()))])
            }
            Self::PrescribedPenetration { node, u_n, gap, step } => (
                ErrorCategory::ContactGeometry,
                "PrescribedPenetration",
                vec![
                    ("node", I(*node)),
                    ("u_n", F(*u_n)),
                    ("gap", F(*gap)),
                    // A static solve has no step: the field says so with −1 … as a Text.
                    ("step", step.map_or(T("static".into()), I)),
                ],
            ),
            Self::SingularStiffness { residual } => {
                (ErrorCategory::Solver, "SingularStiffness", vec![("residual", F(*residual))])
            }
            Self::MemoryBudget { what, needed, budget } => (
                ErrorCategory::Solver,
                "MemoryBudget",
                vec![("what", T(what.clone())), ("needed", F(*needed)), ("budget", F(*budget))],
            ),
            Self::UnknownSetting { name, known } => (
                ErrorCategory::Settings,
                "UnknownSetting",
                vec![("name", T(name.clone())), ("known", T(known.clone()))],
            ),
            Self::BadLoadStep { step, what } => {
                (ErrorCategory::Settings, "BadLoadStep", vec![("step", I(*step)), ("what", T(what.clone()))])
            }
            Self::BadSettingValue { name, what } => (
                ErrorCategory::Settings,
                "BadSettingValue",
                vec![("name", T(name.to_string())), ("what", T(what.clone()))],
            ),
            Self::UnknownChoice { what, got, options } => (
                match *what {
                    "side" | "diagonal" => ErrorCategory::Mesh,
                    "multiplier space" => ErrorCategory::ContactGeometry,
                    _ => ErrorCategory::Settings,
                },
                "UnknownChoice",
                vec![("what", T(what.to_string())), ("got", T(got.clone())), ("options", T(options.clone()))],
            ),
            Self::BadFriction { what } => (ErrorCategory::Settings, "BadFriction", vec![("what", T(what.clone()))]),
            Self::Assembly { matrix, what } => {
                (ErrorCategory::Solver, "Assembly", vec![("matrix", T(matrix.to_string())), ("what", T(what.clone()))])
            }
        }
    }
}
