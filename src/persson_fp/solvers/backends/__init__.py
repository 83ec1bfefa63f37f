"""Adapters to third-party PDE packages (py-pde, FiPy), imported only when their method is chosen."""
