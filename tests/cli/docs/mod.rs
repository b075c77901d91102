//! The documentation's contract with the code: the command-line reference and the man pages
//! are what the clap definitions generate, every flag `--help` lists has an entry, every
//! relative link and image resolves, and every command the README and the book show runs.
//!
//! `GONIOLIGHT_BLESS=1 cargo test --test cli docs::` (or `scripts/gen-docs.sh`) writes the
//! generated pages after a change to the flags.

mod book;
mod examples;
mod generated;
mod links;
mod markdown;
mod reference;
mod scene_file;
