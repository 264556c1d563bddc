"""Linting a description: the driver (one file), network lint, settings from config files,
the lint passes by rule family, and the reporters that print findings.

This package's own namespace stays empty so that importing one part (the reporters for
`odgen diff`, say) does not import the passes.
"""
