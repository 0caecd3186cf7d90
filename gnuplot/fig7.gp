fignum = 7; film_word = 'stiff film'; effect = 'η ≈ 1: the film-substrate transition meets the adhesive one; pull-off reduced (above -3/2)'
load gpdir.'/adhesive_curves.gp'
