"""mechlib: helper library of the executable reproduction."""
