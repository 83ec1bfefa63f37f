"""Problem definitions: :class:`~persson_fp.ContactProblem` (Persson's diffusion problem, Xu et al. tutorial
Eq. 'E:diffusion_equ') and :class:`~persson_fp.FokkerPlanckProblem` (general drift and diffusion)."""
