//! The settings' options of `verbss deform`: one `--NAME VALUE` per setting
//! of the library's table ([`verbss::settings::TABLE`], `-` for `_`), its
//! help and defaults from the table; a switch also bare (`--blend` is
//! `--blend on`). The values are checked by the table
//! ([`Settings::named`]), not here.

use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};
use verbss::settings::{Setting, Settings, Values, TABLE};

/// The settings given on the command line, by name, as given.
#[derive(Debug, Clone, Default)]
pub struct SettingArgs {
    given: Vec<(&'static str, String)>,
}

impl SettingArgs {
    /// The settings of `steps` steps: the given values over the preset of
    /// `method` ([`Settings::named`]).
    pub fn settings(&self, steps: usize) -> verbss::Result<Settings> {
        Settings::named(steps, &self.given)
    }

    /// Whether the setting `name` was given.
    pub fn given(&self, name: &str) -> bool {
        self.given.iter().any(|(n, _)| *n == name)
    }
}

/// The option of `setting`.
fn option(setting: &'static Setting) -> Arg {
    let value = match setting.values {
        Values::Names(_) | Values::Switch | Values::Layer => setting.values.describe(),
        Values::Number { .. } => "X".into(),
        Values::Count { .. } => "K".into(),
    };
    let range = match setting.values {
        Values::Number { .. } | Values::Count { .. } => format!(" ({})", setting.values.describe()),
        _ => String::new(),
    };
    let arg = Arg::new(setting.name)
        .long(setting.flag())
        .value_name(value)
        .help(format!(
            "{}{range} [default: {}]",
            setting.help,
            setting.defaults()
        ))
        .allow_hyphen_values(true)
        .num_args(1);
    match setting.values {
        Values::Switch => arg.num_args(0..=1).default_missing_value("on"),
        _ => arg,
    }
}

impl Args for SettingArgs {
    fn augment_args(cmd: Command) -> Command {
        cmd.args(TABLE.iter().map(option))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        SettingArgs::augment_args(cmd)
    }
}

impl FromArgMatches for SettingArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = SettingArgs::default();
        args.update_from_arg_matches(matches)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for setting in TABLE {
            if let Some(value) = matches.get_one::<String>(setting.name) {
                self.given.retain(|(n, _)| *n != setting.name);
                self.given.push((setting.name, value.clone()));
            }
        }
        Ok(())
    }
}
