"""Stored parameters: the layout of each persistence group and how a stored image migrates."""
