//! FE card exporters (in progress).
