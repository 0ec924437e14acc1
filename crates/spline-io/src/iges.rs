//! IGES 5.3.
