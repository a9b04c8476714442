"""Planners that search directly on the grid graph or on grid cell sequences
(ACO, the path GA family). They share the 8-connected move table below."""
