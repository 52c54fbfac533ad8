"""Instances of :class:`mechlib.calibration.mechanism.Mechanism`: the planar 5R (two legs), a
planar 3-RRR (three legs) and a 6-UPS Gough–Stewart platform (six legs)."""
