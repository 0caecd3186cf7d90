fignum = 4; film_word = 'stiff film'
load gpdir.'/reduced_panels.gp'
