"""Data and analyses of the paper: ``reference.csv`` (the published numbers) and the eigenvalue forensics."""

__all__ = []
