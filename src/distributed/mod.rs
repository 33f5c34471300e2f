//! Renders that outgrow one machine: a render split into parts (tiles or sample ranges),
//! each written as a part file of exact sample sums, merged bit-identically to the whole
//! render; and the Slurm array jobs that run the parts.

mod part;

pub use part::{MAX_PARTS, Part, PartError, Split};
mod merge;
mod metadata;
mod option_words;
mod part_check;
mod part_file;
pub mod slurm;

pub use merge::{
    MergeError, Merged, PartIdentity, check_parts, identity_difference, merge_parts,
    merge_some_parts,
};
pub use metadata::{
    PART_FORMAT, PartMeta, PartTiming, PngSettings, camera_fingerprint, hash_files,
    options_fingerprint, process_cpu_seconds,
};
pub use option_words::options_difference;
pub use part_file::{PartFileError, encode_part, read_part_meta, read_part_sums};
