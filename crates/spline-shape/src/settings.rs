//! The builder methods shared by the constrained approximations (a macro: the builders are
//! different types with the same two settings).

/// The settings shared by the constrained approximations of functions and of surfaces
/// (their builders' `refinement` and `options`), written once.
macro_rules! solver_settings {
    ($refinement:literal) => {
        #[doc = $refinement]
        #[must_use]
        pub fn refinement(mut self, pieces: usize) -> Self {
            self.refinement = pieces;
            self
        }

        /// Sets the barrier method's settings.
        #[must_use]
        pub fn options(mut self, options: BarrierOptions) -> Self {
            self.options = options;
            self
        }
    };
}
