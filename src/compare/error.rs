//! Why a comparison could not run.

/// Why a comparison could not run.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// Reading or writing the output folder failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// Slurm refused or is not there.
    #[error(transparent)]
    Slurm(#[from] crate::slurm::SlurmError),
}
