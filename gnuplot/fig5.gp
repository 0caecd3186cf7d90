fignum = 5; film_word = 'soft film'; effect = 'η ≲ 1: the film-substrate transition meets the adhesive one; pull-off enhanced (below -3/2)'
load gpdir.'/adhesive_curves.gp'
