fignum = 3; film_word = 'soft film'
load gpdir.'/reduced_panels.gp'
