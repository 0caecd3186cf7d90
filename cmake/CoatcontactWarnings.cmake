# cc_set_warnings(target): warnings on, per target, per language.
function(cc_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic>
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra>
    $<$<COMPILE_LANGUAGE:Fortran>:-Wall -std=f2018 -fimplicit-none>)
  if(COATCONTACT_SANITIZE)
    target_compile_options(${target} PRIVATE
      $<$<COMPILE_LANGUAGE:CXX>:-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all>
      $<$<COMPILE_LANGUAGE:C>:-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all>
      # no-recursion: gfortran's recursion check is a static flag per procedure, so it reports
      # concurrent calls from several threads (the solver's OpenMP sweep evaluates the kernel
      # table in parallel) as recursion; every other -fcheck=all check stays on.
      $<$<COMPILE_LANGUAGE:Fortran>:-fcheck=all,no-recursion -fsanitize=address -fno-omit-frame-pointer>)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
