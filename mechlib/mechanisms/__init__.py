"""Instances of :class:`mechlib.calibration.mechanism.Mechanism` beyond the 5R (whose instance is
:mod:`mechlib.fivebar.mechanism`): a planar 3-RRR (three legs) and a 6-UPS Gough–Stewart
platform (six legs). The catalogue of the "Beyond the 5R" studies that assembles them with the
5R is :mod:`mechlib.mechanism_catalog`, above both packages."""
