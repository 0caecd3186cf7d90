fignum = 5; film_word = 'soft film'; effect = 'η ≲ 1: the film-substrate transition meets the adhesive one; pull-off enhanced (below -3/2)'
# The thin films' curves rise through the top left: the key goes to the empty lower right.
key_position = 'bottom right samplen 2 spacing 0.95'
load gpdir.'/adhesive_curves.gp'
