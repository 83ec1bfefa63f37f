"""The general finite-volume engine: conservative fluxes and walls on a cell grid, its time steps, the front-fixed
moving yield wall, and the method of lines on the same fluxes."""
