"""The physics with closed forms or quadratures (imports only numpy, scipy and :mod:`persson_fp.surfaces`): the image
and strip solutions, fudge factors, the effective variance, hardness models, mean separation and stiffness."""
