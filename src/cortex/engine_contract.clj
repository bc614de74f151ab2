;; Generated from org/engine-contract.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine-contract
  "What a physics engine gives the rest of cortex: the public vars of
  `cortex.engine`, as data. Each engine's namespace defines them all;
  cortex.engine-contract-test checks the running one.")

(def provides
  "name -> [arities what], arities the number of arguments of each
  arglist, or :value for a var that is not a function."
  '{;; what it is
    name [:value "which engine this is: :jbullet or :native"]
    label [:value "the engine's name as people read it, for reports"]
    ;; spaces
    configure-space! [[1] "set a PhysicsSpace up as cortex simulates"]
    solver-iterations [:value "the solver's passes per Bullet step in cortex's spaces"]
    blender-solver-order! [[1] "visit a space's constraints in the order Blender's world does"]
    blender-velocities! [[2] "before a substep of dt: the velocities Blender's Bullet gives bodies before its solver (damping, gyroscopic term), where the engine's own differ"]
    add-all! [[2] "add the bodies under a spatial, and their joints, to a space"]
    reduce-contacts [[5] "fold a function over the contact manifolds of a space's last step"]
    collision-object [[1] "what the contact manifolds name a body by"]
    ;; shapes
    hull-margin [[0] "the collision margin cortex gives hull shapes"]
    thin [:value "the thickness below which a body is small (the shapes chapter)"]
    thickness [[1] "how thick a convex shape counts as (a compound's thinnest child): its smallest extent along its axes, a sheet's a tenth of the next; or nil"]
    hull-points [[1] "the points of a hull shape (of a compound's first child), or nil"]
    hull-volume [[1] "the volume of the convex hull of points [[x y z] ...]"]
    mesh-shape [[1] "a static triangle-mesh shape of a jME mesh"]
    gimpact-shape [[1] "a moving triangle-mesh shape of a jME mesh"]
    ;; bodies
    rigid-body [[1] "the engine's own object for a jME body"]
    set-inertia! [[3] "give a body its mass and principal moments"]
    clear-inertia! [[1] "make a body unable to turn"]
    set-sleep! [[2] ":start-asleep or :never"]
    set-collections! [[2] "put a body in Blender's collision collections (20 bits)"]
    joints [[1] "the joints attached to a jME body"]
    position [[1] "an engine body's centre of mass now, [x y z]"]
    orientation [[1] "an engine body's rotation now, [x y z w]"]
    rotation-matrix [[1] "a jME body's rotation now, a new Matrix3f"]
    linear-velocity [[1] "an engine body's velocity now, [x y z]"]
    angular-velocity [[1] "an engine body's angular velocity now, [x y z]"]
    body-states [[1] "many engine bodies' states now, 13 doubles each, in one array"]
    inverse-mass [[1] "1/m of an engine body, 0 for a static one"]
    inverse-inertia [[1] "the inverse principal moments of an engine body, [x y z]"]
    apply-torques! [[3] "torque t on one engine body and -t on another"]
    ;; joints
    six-dof-class [:value "the class of the joints six-dof-joint makes"]
    six-dof-joint [[7] "a six-degree-of-freedom joint between two bodies, limited"]
    six-dof-angles [[1] "a six-DOF joint's three angles now"]
    six-dof-safe-middle [:value "the widest middle angle a six-DOF joint is given"]
    spring-joint [[9] "a six-DOF joint whose three angles are sprung towards the pose it was built in"]
    hinge-limits [[1] "the limits to give a jME HingeJoint for the designer's [lo hi]"]
    limit-hinge! [[3] "limit a HingeJoint to [low high] in the engine's sense of its angle"]
    frame-hinge-limit [[1] "the limit to give a FrameHingeJoint so that it stops at an angle"]
    zero-hinge! [[1] "make a HingeJoint read 0 where its bodies are now"]
    limit-rows! [[2] "give a hinge or cone rows of its own that hold its limits"]
    joint-frames [[1] "the frames a joint is read in, when the engine keeps them"]
    pivots [[1] "a joint's point in each of its bodies' frames"]
    collide-linked! [[2] "whether the two bodies a joint links collide"]
    collide-linked? [[1] "do the two bodies a joint links collide?"]
    applied-impulse [[1] "the impulse a joint applied in the last step"]
    breaking-threshold! [[2] "make a joint breakable at a threshold"]
    broken? [[2] "whether a breakable joint broke in the last substep"]})
