//! Names of the fieldless option enums: each variant's name on the command line, in the C ABI
//! and in the reports, and its parse back (`FromStr`) with an error that lists the names.

/// `name()` and `FromStr` for a fieldless enum with `Default` and `PartialEq`:
/// `named_enum!(Type, "what it is", Variant => "name", ...)`. Names parse case-insensitively;
/// an unknown one is refused with the list of names, the default's marked.
macro_rules! named_enum {
    ($ty:ident, $what:literal, $($variant:ident => $name:literal),+ $(,)?) => {
        impl $ty {
            /// The name used by the command line and the reports.
            pub fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name,)+
                }
            }
        }

        impl std::str::FromStr for $ty {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                match s.to_ascii_lowercase().as_str() {
                    $($name => Ok($ty::$variant),)+
                    _ => Err(format!("unknown {} {s:?}: use {}", $what, $crate::named::choices(&[$(($name, $ty::$variant == $ty::default())),+]))),
                }
            }
        }
    };
}
pub(crate) use named_enum;

/// The names as a sentence's list ("a (default), b or c"), the default's marked.
pub(crate) fn choices(names: &[(&str, bool)]) -> String {
    let named: Vec<String> = names.iter().map(|&(n, default)| if default { format!("{n} (default)") } else { n.to_string() }).collect();
    match named.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        Some((last, _)) => last.clone(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    #[derive(Debug, Clone, Copy, PartialEq, Default)]
    enum Fruit {
        #[default]
        Apple,
        Pear,
        Quince,
    }
    named_enum!(Fruit, "fruit", Apple => "apple", Pear => "pear", Quince => "quince");

    #[test]
    fn names_parse_back_and_unknown_ones_are_listed() {
        for f in [Fruit::Apple, Fruit::Pear, Fruit::Quince] {
            assert_eq!(f.name().parse::<Fruit>(), Ok(f));
        }
        assert_eq!("PEAR".parse::<Fruit>(), Ok(Fruit::Pear));
        assert_eq!("plum".parse::<Fruit>(), Err("unknown fruit \"plum\": use apple (default), pear or quince".to_string()));
    }
}
