//! The published shapegen generators: spaceship, three-branch tree and city.
