"""Pure physics: materials, rheology, asperity contact, elasticity, friction, regimes."""
