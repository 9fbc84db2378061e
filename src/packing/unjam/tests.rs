//! Tests of the unjamming moves on small scenes.
