"""Instances of :class:`mechlib.calibration.mechanism.Mechanism` beyond the 5R (whose instance is
:mod:`mechlib.fivebar.mechanism`): a planar 3-RRR (three legs) and a 6-UPS Gough–Stewart
platform (six legs); and the catalog of the "Beyond the 5R" studies."""
