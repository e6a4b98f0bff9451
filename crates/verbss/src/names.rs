//! The one spelling of every named setting: [`named!`] gives an enum its
//! names, [`std::str::FromStr`] and [`std::fmt::Display`] from one table, so
//! the command line, case files, Python, C and reports all read and write
//! the same words.

/// `named!(Type, "what", [Variant => "name", …], [alias => Variant, …])`:
/// `Type::NAMES`, `Type::name`, `Display` and `FromStr` (accepting the
/// aliases too; the error names `what` and every name).
macro_rules! named {
    ($ty:ident, $what:literal, [$($variant:ident => $name:literal),+ $(,)?]
        $(, [$($alias:literal => $target:ident),* $(,)?])?) => {
        impl $ty {
            /// Every name, in order.
            pub const NAMES: &'static [&'static str] = &[$($name),+];

            /// The name of this value.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = crate::error::Error;

            fn from_str(s: &str) -> crate::error::Result<$ty> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    $($($alias => Ok($ty::$target),)*)?
                    _ => Err(crate::error::Error::InvalidSetting(format!(
                        "unknown {} '{s}' (expected {})",
                        $what,
                        crate::names::one_of(Self::NAMES)
                    ))),
                }
            }
        }
    };
}

pub(crate) use named;

/// `a, b or c`.
pub(crate) fn one_of(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [rest @ .., last] => format!("{} or {last}", rest.join(", ")),
    }
}
