//! The one status vocabulary: every solve reports one of these, never a silent wrong number.
//! Codes follow scipy's elementwise solvers where they overlap (0, -2, -3).

/// Outcome of solving one point. `#[repr(i8)]`: sweeps store it in an `i8` array.
#[repr(i8)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    /// Residual and next Newton correction below `tol`, on the requested assembly mode.
    Converged = 0,
    /// `max_iter` Newton steps were taken without reaching `tol`.
    MaxIterations = -2,
    /// The input value, a residual or an iterate was NaN or infinite.
    NonFinite = -3,
    /// The conditioning |sin(theta4 - theta3)| min(r3, r4) / L fell below the singular
    /// threshold: a dead (toggle) or change point, where the two assembly modes meet.
    Singular = -4,
    /// The loop cannot close at this input value (crank angle or displacement), known from
    /// the geometry before any iteration.
    NotAssemblable = -5,
    /// Newton converged, but on the other assembly mode than the one requested.
    BranchJump = -6,
    /// The residual is below `tol` but rounding keeps the Newton correction above it: `tol`
    /// asks for more than double precision resolves at this conditioning.
    PrecisionLoss = -7,
    /// The input angle lies past a dead point of a group on the circuit being followed:
    /// the motion must reverse there (a turning point); the sweep reports its input angle.
    Limit = -8,
}

impl Status {
    /// All statuses, in code order from 0 down.
    pub const ALL: [Status; 8] = [
        Status::Converged,
        Status::MaxIterations,
        Status::NonFinite,
        Status::Singular,
        Status::NotAssemblable,
        Status::BranchJump,
        Status::PrecisionLoss,
        Status::Limit,
    ];

    /// The `i8` code stored in status arrays.
    #[inline]
    pub fn code(self) -> i8 {
        self as i8
    }

    /// True only for [`Status::Converged`].
    #[inline]
    pub fn is_success(self) -> bool {
        self == Status::Converged
    }

    /// The status's name as every binding spells it (Python's `planarkin.Status` member,
    /// the page's JSON): upper case with underscores, e.g. `"NOT_ASSEMBLABLE"`.
    pub fn name(self) -> &'static str {
        match self {
            Status::Converged => "CONVERGED",
            Status::MaxIterations => "MAX_ITERATIONS",
            Status::NonFinite => "NON_FINITE",
            Status::Singular => "SINGULAR",
            Status::NotAssemblable => "NOT_ASSEMBLABLE",
            Status::BranchJump => "BRANCH_JUMP",
            Status::PrecisionLoss => "PRECISION_LOSS",
            Status::Limit => "LIMIT",
        }
    }

    /// The status of an `i8` code, None for a code that is no status.
    pub fn from_code(code: i8) -> Option<Status> {
        Status::ALL.into_iter().find(|s| s.code() == code)
    }

    /// A one-line human-readable message.
    pub fn message(self) -> &'static str {
        match self {
            Status::Converged => "converged: residual and Newton correction below tolerance on the requested mode",
            Status::MaxIterations => "maximum number of iterations reached without convergence",
            Status::NonFinite => "a non-finite value (NaN or infinity) was met",
            Status::Singular => "singular: dead (toggle) or change point, the two modes meet",
            Status::NotAssemblable => "not assemblable: the loop cannot close at this input value",
            Status::BranchJump => "converged on the other assembly mode than the one requested",
            Status::PrecisionLoss => "tolerance below what double precision resolves at this point",
            Status::Limit => "past a dead point of the circuit followed: the input must reverse there",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Status;

    #[test]
    fn names_are_distinct_upper_snake_case_and_codes_round_trip() {
        for (i, s) in Status::ALL.iter().enumerate() {
            assert!(s.name().chars().all(|c| c.is_ascii_uppercase() || c == '_'), "{s:?}");
            assert!(Status::ALL[..i].iter().all(|t| t.name() != s.name() && t.code() != s.code()));
            assert_eq!(Status::from_code(s.code()), Some(*s));
        }
        assert_eq!(Status::from_code(1), None);
        assert_eq!(Status::NotAssemblable.name(), "NOT_ASSEMBLABLE");
    }
}
