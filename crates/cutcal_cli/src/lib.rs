//! cutcal CLI library.
